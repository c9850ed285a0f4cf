#include "mm/maneuver_samples.hpp"

#include <algorithm>

namespace mm {

index_range maneuver_samples::grid(family f) const {
  const std::size_t brake_size = brake.samples.size();
  if (f == family::brake) return {0, brake_size};
  return {brake_size, brake_size + accelerate.samples.size()};
}

index_range maneuver_samples::nominal_column(family f) const {
  const std::size_t start = brake.samples.size() + accelerate.samples.size();
  if (f == family::brake) return {start, start + brake.acceleration_count};
  return {start + brake.acceleration_count, start + brake.acceleration_count + accelerate.acceleration_count};
}

double maneuver_samples::total_weight(family f) const {
  double total = 0.0;
  const index_range r = grid(f);
  for (std::size_t i = r.begin; i < r.end; ++i) total += area_weights[i];
  return total;
}

maneuver_samples sample_maneuvers(const ego_state& ego, double nominal_curvature, double horizon,
                                  const sampling_resolution& resolution, bool node_weights, bool end_points) {
  maneuver_samples out;
  out.brake = available_displacements(ego.speed, ego.limits, horizon, family::brake, resolution, node_weights, end_points);
  out.accelerate =
      available_displacements(ego.speed, ego.limits, horizon, family::accelerate, resolution, node_weights, end_points);
  const double kappa_max = out.brake.max_curvature;
  out.nominal_curvature = std::clamp(nominal_curvature, -kappa_max, kappa_max);

  const auto add = [&](const maneuver& u, family f, double weight, vec2 end) {
    out.maneuvers.push_back(u);
    out.families.push_back(f);
    out.area_weights.push_back(weight);
    out.end_points.push_back(end);
  };
  for (const displacement_set* set : {&out.brake, &out.accelerate}) {
    for (const displacement_sample& s : set->samples) add(s.u, set->fam, s.area_weight, s.end_point);
  }
  for (const displacement_set* set : {&out.brake, &out.accelerate}) {
    for (std::size_t ia = 0; ia < set->acceleration_count; ++ia) {
      const double a = set->samples[ia * set->curvature_count].u.acceleration;
      const double s = travelled_distance(ego.speed, a, horizon, ego.limits.speed_cap);
      add({a, out.nominal_curvature}, set->fam, 0.0, end_points ? arc_point(out.nominal_curvature, s) : vec2{});
    }
  }
  return out;
}

}  // namespace mm
