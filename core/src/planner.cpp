#include "mm/planner.hpp"

#include <cmath>

#include "pipeline.hpp"

namespace mm {

std::vector<double> forecast_times(const planner_config& config) {
  std::vector<double> taus(config.forecast_count);
  for (std::size_t i = 0; i < taus.size(); ++i) taus[i] = static_cast<double>(i) * config.forecast_step;
  return taus;
}

double sample_time_count(double duration, double step) { return std::ceil(duration / step - 1e-9) + 1.0; }

double sampled_maneuver_count(const sampling_resolution& resolution) {
  return 2.0 * static_cast<double>(resolution.accelerations) * static_cast<double>(resolution.curvatures);
}

plan_result plan(const plan_input& input) {
  return detail::run_pipeline(input, {input.config.resolution, input.config.max_time_step, false,
                                      input.config.assignment_search});
}

planner::planner() : cache_(std::make_unique<detail::planning_cache>()) {}
planner::~planner() = default;
planner::planner(planner&&) noexcept = default;
planner& planner::operator=(planner&&) noexcept = default;

plan_result planner::plan(const plan_input& input) {
  if (!cache_) cache_ = std::make_unique<detail::planning_cache>();
  return detail::run_pipeline(input,
                              {input.config.resolution, input.config.max_time_step, false, input.config.assignment_search},
                              cache_.get());
}

}  // namespace mm
