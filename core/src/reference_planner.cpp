#include "mm/reference_planner.hpp"

#include "pipeline.hpp"

namespace mm {

sampling_resolution reference_grid(const ego_limits& limits, const reference_resolution& resolution) {
  return limits.steering ? resolution.sampling : sampling_resolution{resolution.one_dimensional_accelerations, 1};
}

plan_result plan_reference(const plan_input& input, const reference_resolution& resolution) {
  return detail::run_pipeline(input, {reference_grid(input.ego.limits, resolution), 0.01, true,
                                      assignment_search_kind::exhaustive, resolution.proof_resolution});
}

}  // namespace mm
