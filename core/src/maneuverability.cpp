#include "mm/maneuverability.hpp"

#include <algorithm>

namespace mm {

double maneuverability_index(const maneuver_samples& samples, family f, const sample_mask& colliding) {
  const index_range r = samples.grid(f);
  double total = 0.0;
  double unsafe = 0.0;
  for (std::size_t i = r.begin; i < r.end; ++i) {
    total += samples.area_weights[i];
    if (colliding.test(i)) unsafe += samples.area_weights[i];
  }
  if (total <= 0.0) return colliding.all_in(r.begin, r.end) ? 0.0 : 1.0;
  return std::clamp((total - unsafe) / total, 0.0, 1.0);
}

maneuverability_pair maneuverability_indices(const maneuver_samples& samples, const sample_mask& colliding) {
  return {maneuverability_index(samples, family::brake, colliding),
          maneuverability_index(samples, family::accelerate, colliding)};
}

std::vector<std::uint8_t> excluded_forecast_times(std::span<const double> forecast_times,
                                                  double time_to_collision) {
  std::vector<std::uint8_t> excluded(forecast_times.size(), 0);
  for (std::size_t i = 1; i < forecast_times.size(); ++i) {
    excluded[i] = forecast_times[i] > time_to_collision ? 1 : 0;
  }
  return excluded;
}

}  // namespace mm
