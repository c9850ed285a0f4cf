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
  const std::size_t grid_size = out.brake.samples.size() + out.accelerate.samples.size();
  const std::size_t column_size = out.brake.acceleration_count + out.accelerate.acceleration_count;
  out.maneuvers.reserve(grid_size + column_size);
  out.families.reserve(grid_size + column_size);
  out.area_weights.reserve(grid_size + column_size);
  out.end_points.reserve(grid_size + column_size);
  for (const displacement_set* set : {&out.brake, &out.accelerate}) {
    for (const displacement_sample& s : set->samples) {
      out.maneuvers.push_back(s.u);
      out.families.push_back(set->fam);
      out.area_weights.push_back(s.area_weight);
      out.end_points.push_back(s.end_point);
    }
  }
  set_nominal_curvature(out, ego, nominal_curvature, horizon, end_points);
  return out;
}

void set_nominal_curvature(maneuver_samples& samples, const ego_state& ego, double nominal_curvature, double horizon,
                           bool end_points) {
  const std::size_t grid_size = samples.brake.samples.size() + samples.accelerate.samples.size();
  samples.maneuvers.resize(grid_size);
  samples.families.resize(grid_size);
  samples.area_weights.resize(grid_size);
  samples.end_points.resize(grid_size);
  const double kappa_max = samples.brake.max_curvature;
  samples.nominal_curvature = std::clamp(nominal_curvature, -kappa_max, kappa_max);
  for (const displacement_set* set : {&samples.brake, &samples.accelerate}) {
    for (std::size_t ia = 0; ia < set->acceleration_count; ++ia) {
      const double a = set->samples[ia * set->curvature_count].u.acceleration;
      const double s = travelled_distance(ego.speed, a, horizon, ego.limits.speed_cap);
      samples.maneuvers.push_back({a, samples.nominal_curvature});
      samples.families.push_back(set->fam);
      samples.area_weights.push_back(0.0);
      samples.end_points.push_back(end_points ? arc_point(samples.nominal_curvature, s) : vec2{});
    }
  }
}

}  // namespace mm
