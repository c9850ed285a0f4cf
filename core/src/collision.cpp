#include "mm/collision.hpp"

#include <algorithm>
#include <cmath>

namespace mm {
namespace {

/// Whether the ego executing `u` and the obstacle forecast with `forecast_time` overlap at time t,
/// and the squared distance of their reference points [m²].
struct overlap_check {
  bool overlaps;
  double squared_distance;
};

overlap_check check_overlap(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle,
                            double forecast_time, double t, const collision_window& window) {
  const pose ego_pose = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
  const pose obstacle_pose = forecast_pose(obstacle.motion, forecast_time, t);
  // Footprints lie within their bounding discs: apart when the discs are.
  const double reach = bounding_radius(ego.shape) + bounding_radius(obstacle.shape) + window.margin;
  const double squared = squared_norm(ego_pose.position - obstacle_pose.position);
  if (squared >= reach * reach) return {false, squared};
  return {overlaps(place(ego.shape, ego_pose), place(obstacle.shape, obstacle_pose), window.margin), squared};
}

bool overlaps_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle,
                 double forecast_time, double t, const collision_window& window) {
  return check_overlap(ego, u, obstacle, forecast_time, t, window).overlaps;
}

/// The first time of overlap in (free, hit] to 1e-4 s, by bisection: none at `free`, one at `hit`
/// (the obstacle forecast with its CTRV motion for the whole window).
double bisected_collision(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle,
                          const collision_window& window, double free, double hit) {
  while (hit - free > 1e-4) {
    const double mid = 0.5 * (free + hit);
    (overlaps_at(ego, nominal, obstacle, window.duration, mid, window) ? hit : free) = mid;
  }
  return hit;
}

}  // namespace

std::vector<double> sample_times(double duration, double step) {
  const auto steps = static_cast<std::size_t>(std::ceil(duration / step - 1e-9));
  std::vector<double> times(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) times[k] = std::min(duration, static_cast<double>(k) * step);
  return times;
}

double tunneling_time_step(const ego_state& ego, const forecast_obstacle& obstacle,
                           const collision_window& window) {
  const double ego_top_speed =
      speed_after(ego.speed, ego.limits.max_acceleration, window.horizon, ego.limits.speed_cap);
  const double relative_speed = ego_top_speed + obstacle.motion.speed;
  const double dimension = std::min(smallest_dimension(ego.shape), smallest_dimension(obstacle.shape));
  if (relative_speed <= 0.0) return window.duration;
  return dimension / relative_speed;
}

double first_collision_time(const ego_state& ego, const maneuver& u,
                            std::span<const forecast_obstacle> obstacles,
                            std::span<const double> forecast_times, const collision_window& window) {
  for (const double t : sample_times(window.duration, window.time_step)) {
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      if (overlaps_at(ego, u, obstacles[j], forecast_times[j], t, window)) return t;
    }
  }
  return no_collision;
}

bool maneuver_collides(const ego_state& ego, const maneuver& u,
                       std::span<const forecast_obstacle> obstacles,
                       std::span<const double> forecast_times, const collision_window& window) {
  return first_collision_time(ego, u, obstacles, forecast_times, window) != no_collision;
}

bool verified_collision_free(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                             std::span<const double> forecast_times, const collision_window& window,
                             double resolution) {
  // Largest speed of the ego's reference point along u, and of any of its footprint points.
  const double top_speed = std::max(std::min(ego.speed, ego.limits.speed_cap),
                                    speed_after(ego.speed, u.acceleration, window.horizon, ego.limits.speed_cap));
  const double ego_rate = top_speed * (1.0 + std::abs(u.curvature) * bounding_radius(ego.shape));
  double t = 0.0;
  while (true) {
    const pose ego_pose = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
    const placed_footprint e = place(ego.shape, ego_pose);
    double step = window.duration - t;
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      const forecast_obstacle& o = obstacles[j];
      const double rate = ego_rate + o.motion.speed + std::abs(o.motion.yaw_rate) * bounding_radius(o.shape);
      const double clearance =
          signed_distance(e, place(o.shape, forecast_pose(o.motion, forecast_times[j], t))) - window.margin;
      if (clearance <= 0.0) return false;
      if (rate > 0.0) step = std::min(step, clearance / rate);
    }
    if (t >= window.duration) return true;
    if (step < resolution) return false;
    t = std::min(window.duration, t + step);
  }
}

double time_to_collision(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle,
                         const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  const double cap = ego.limits.speed_cap;
  const double reach = bounding_radius(ego.shape) + bounding_radius(obstacle.shape) + window.margin;
  // The reference points' distance changes no faster than the sum of their largest speeds, so from
  // a time at which the bounding discs are apart by `gap` none can overlap for gap / rate.
  const double rate = std::max(std::clamp(ego.speed, 0.0, cap),
                               speed_after(ego.speed, nominal.acceleration, window.horizon, cap)) +
                      std::abs(obstacle.motion.speed);
  for (std::size_t k = 0; k < times.size();) {
    const double t = times[k];
    const overlap_check at = check_overlap(ego, nominal, obstacle, window.duration, t, window);
    if (at.overlaps) {
      if (t == 0.0) return 0.0;
      return bisected_collision(ego, nominal, obstacle, window, times[k - 1], t);
    }
    // Skipped times are provably apart (lowered by a rounding slack); the grid's steps are ≤ time_step.
    const double gap = std::sqrt(at.squared_distance) - reach - 1e-9;
    std::size_t skip = 0;
    if (gap > 0.0 && rate > 0.0) {
      const double steps = gap * (1.0 - 1e-9) / (rate * window.time_step);
      skip = steps >= static_cast<double>(times.size()) ? times.size() : static_cast<std::size_t>(steps);
    } else if (gap > 0.0) {
      skip = times.size();
    }
    k += skip + 1;
  }
  return no_collision;
}

double time_to_collision_reference(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle,
                                   const collision_window& window) {
  double previous = 0.0;
  for (const double t : sample_times(window.duration, window.time_step)) {
    if (overlaps_at(ego, nominal, obstacle, window.duration, t, window)) {
      if (t == 0.0) return 0.0;
      return bisected_collision(ego, nominal, obstacle, window, previous, t);
    }
    previous = t;
  }
  return no_collision;
}

}  // namespace mm
