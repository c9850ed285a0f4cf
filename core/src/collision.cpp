#include "mm/collision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "mm/translation.hpp"

namespace mm {
namespace {

/// Whether the ego executing `u` and the obstacle forecast with `forecast_time` overlap at time t,
/// and the squared distance of their reference points [m²].
struct overlap_check {
  bool overlaps;
  double squared_distance;
};

/// The test of the placed footprints; `reach` [m] is the sum of their bounding radii and the margin.
overlap_check check_overlap(const footprint& ego_shape, const pose& ego_pose, const footprint& obstacle_shape,
                            const pose& obstacle_pose, double reach, double margin) {
  // Footprints lie within their bounding discs: apart when the discs are.
  const double squared = squared_norm(ego_pose.position - obstacle_pose.position);
  if (squared >= reach * reach) return {false, squared};
  return {overlaps(place(ego_shape, ego_pose), place(obstacle_shape, obstacle_pose), margin), squared};
}

overlap_check check_overlap(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle,
                            double forecast_time, double t, const collision_window& window) {
  const pose ego_pose = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
  const pose obstacle_pose = forecast_pose(obstacle.motion, forecast_time, t);
  const double reach = bounding_radius(ego.shape) + bounding_radius(obstacle.shape) + window.margin;
  return check_overlap(ego.shape, ego_pose, obstacle.shape, obstacle_pose, reach, window.margin);
}

bool overlaps_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle,
                 double forecast_time, double t, const collision_window& window) {
  return check_overlap(ego, u, obstacle, forecast_time, t, window).overlaps;
}

/// Sample times after index k that the bounding discs, `squared_distance` [m²] apart in their
/// centres at t_k, cannot close: the centres approach at most at `rate` [m/s] (lowered by a
/// rounding slack; the grid's steps are ≤ time_step).
std::size_t times_apart(double squared_distance, double reach, double rate, std::size_t count,
                        const collision_window& window) {
  const double gap = std::sqrt(squared_distance) - reach - 1e-9;
  if (!(gap > 0.0)) return 0;
  if (!(rate > 0.0)) return count;
  const double steps = gap * (1.0 - 1e-9) / (rate * window.time_step);
  return steps >= static_cast<double>(count) ? count : static_cast<std::size_t>(steps);
}

}  // namespace

double largest_speed(const ego_state& ego, const maneuver& u, double horizon) {
  const double cap = ego.limits.speed_cap;
  return std::max(std::min(ego.speed, cap), speed_after(ego.speed, u.acceleration, horizon, cap));
}

double largest_point_speed(double largest_speed, double curvature, double radius) {
  return largest_speed * (1.0 + std::abs(curvature) * radius);
}

double largest_point_speed(const ego_state& ego, const maneuver& u, double horizon) {
  return largest_point_speed(largest_speed(ego, u, horizon), u.curvature, bounding_radius(ego.shape));
}

double largest_point_speed(const forecast_obstacle& obstacle) {
  return obstacle.motion.speed + std::abs(obstacle.motion.yaw_rate) * bounding_radius(obstacle.shape);
}

namespace {

/// The times of `sample_times(duration, step)` without the list: how many, and the k-th [s].
struct sample_grid {
  std::size_t count;
  double duration;
  double step;
  double at(std::size_t k) const { return std::min(duration, static_cast<double>(k) * step); }
};

sample_grid sample_grid_of(double duration, double step) {
  return {static_cast<std::size_t>(std::ceil(duration / step - 1e-9)) + 1, duration, step};
}

}  // namespace

std::vector<double> sample_times(double duration, double step) {
  const sample_grid grid = sample_grid_of(duration, step);
  std::vector<double> times(grid.count);
  for (std::size_t k = 0; k < grid.count; ++k) times[k] = grid.at(k);
  return times;
}

double tunneling_relative_speed(const ego_state& ego, const forecast_obstacle& obstacle,
                                const collision_window& window) {
  return speed_after(ego.speed, ego.limits.max_acceleration, window.horizon, ego.limits.speed_cap) +
         obstacle.motion.speed;
}

double tunneling_time_step(const ego_state& ego, const forecast_obstacle& obstacle,
                           const collision_window& window) {
  const double relative_speed = tunneling_relative_speed(ego, obstacle, window);
  const double dimension = std::min(smallest_dimension(ego.shape), smallest_dimension(obstacle.shape));
  if (relative_speed <= 0.0) return window.duration;
  return dimension / relative_speed;
}

namespace {

/// What `first_collision_time` needs of one obstacle at every sample time: its forecast pose,
/// placed on first use and kept for every maneuver.
struct forecast_track {
  const forecast_obstacle* obstacle;
  double forecast_time;
  double reach;  ///< bounding radii of ego and obstacle plus the margin [m]
  std::vector<pose> poses;
  std::vector<std::uint8_t> known;
  const pose& at(std::size_t k, double t) {
    if (!known[k]) {
      poses[k] = forecast_pose(obstacle->motion, forecast_time, t);
      known[k] = 1;
    }
    return poses[k];
  }
};

std::vector<forecast_track> forecast_tracks(const ego_state& ego, std::span<const forecast_obstacle> obstacles,
                                            std::span<const double> forecast_times, const collision_window& window,
                                            std::size_t count) {
  std::vector<forecast_track> tracks;
  const double ego_radius = bounding_radius(ego.shape);
  for (std::size_t j = 0; j < obstacles.size(); ++j) {
    tracks.push_back({&obstacles[j], forecast_times[j], ego_radius + bounding_radius(obstacles[j].shape) + window.margin,
                      std::vector<pose>(count), std::vector<std::uint8_t>(count, 0)});
  }
  return tracks;
}

/// `first_collision_time` of `u` against `tracks` on the sample times `times`; `next` is scratch.
double first_collision_on(const ego_state& ego, const maneuver& u, std::span<forecast_track> tracks,
                          std::span<const double> times, const collision_window& window,
                          std::vector<std::size_t>& next) {
  const double ego_speed = largest_speed(ego, u, window.horizon);
  // next[j]: the first time index at which obstacle j can overlap.
  next.assign(tracks.size(), 0);
  for (std::size_t k = 0; k < times.size();) {
    std::size_t after = times.size();
    std::optional<pose> ego_pose;
    for (std::size_t j = 0; j < tracks.size(); ++j) {
      if (next[j] == k) {
        forecast_track& track = tracks[j];
        if (!ego_pose) ego_pose = maneuver_pose(ego.pose, ego.speed, u, times[k], window.horizon, ego.limits.speed_cap);
        const overlap_check at = check_overlap(ego.shape, *ego_pose, track.obstacle->shape, track.at(k, times[k]),
                                               track.reach, window.margin);
        if (at.overlaps) return times[k];
        const double rate = ego_speed + std::abs(track.obstacle->motion.speed);
        next[j] = k + times_apart(at.squared_distance, track.reach, rate, times.size(), window) + 1;
      }
      after = std::min(after, next[j]);
    }
    k = after;
  }
  return no_collision;
}

}  // namespace

double first_collision_time(const ego_state& ego, const maneuver& u,
                            std::span<const forecast_obstacle> obstacles,
                            std::span<const double> forecast_times, const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  std::vector<forecast_track> tracks = forecast_tracks(ego, obstacles, forecast_times, window, times.size());
  std::vector<std::size_t> next;
  return first_collision_on(ego, u, tracks, times, window, next);
}

std::vector<double> first_collision_times(const ego_state& ego, std::span<const maneuver> maneuvers,
                                          std::span<const forecast_obstacle> obstacles,
                                          std::span<const double> forecast_times, const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  std::vector<forecast_track> tracks = forecast_tracks(ego, obstacles, forecast_times, window, times.size());
  std::vector<std::size_t> next;
  std::vector<double> first;
  first.reserve(maneuvers.size());
  for (const maneuver& u : maneuvers) first.push_back(first_collision_on(ego, u, tracks, times, window, next));
  return first;
}

double first_collision_time_reference(const ego_state& ego, const maneuver& u,
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

namespace {

/// How the ego executing `u` moves at time t [s]: its reference point's velocity [m/s], and bounds
/// over [t, T_c] of its turn rate [rad/s] and of its reference point's acceleration [m/s²]:
/// |κ|·v_max and |a| + |κ|·v_max² on the arc (t < T_h), 0 on the straight part after it.
struct ego_motion_at {
  vec2 velocity;
  double turn_rate;
  double acceleration;
};

ego_motion_at ego_motion(const ego_state& ego, const maneuver& u, const pose& at, double t,
                         const collision_window& window, double largest) {
  const double speed = speed_after(ego.speed, u.acceleration, std::min(t, window.horizon), ego.limits.speed_cap);
  const vec2 velocity{speed * std::cos(at.heading), speed * std::sin(at.heading)};
  if (t >= window.horizon) return {velocity, 0.0, 0.0};
  const double turn = std::abs(u.curvature) * largest;
  return {velocity, turn, std::abs(u.acceleration) + turn * largest};
}

/// The proof's translation bound (`proof_steps::translation_bound`, docs/method.md §4.5): over [t, t + h] a footprint stays within its
/// placement at t moved at its reference point's velocity at t, widened by R·ω·s + A·s²/2 at t + s
/// (R its bounding radius, ω and A bounds of its turn rate and of its reference point's
/// acceleration), so the signed distance at t + s is at least that of the two moved placements less
/// ρ·s + A·s²/2, ρ = R_e·ω_e + R_o·ω_o, A = A_e + A_o. Returns the longest
/// h = min(longest_translated_step, remaining)·2^−k longer than `shorter_than_this` [s] for which the
/// smallest signed distance of the moved placements over [0, h] (closed form) exceeds the margin
/// by more than ρ·h + A·h²/2; 0 when there is none.
double translated_step(const placed_footprint& ego, const ego_motion_at& ego_moves, double ego_radius,
                       const placed_footprint& obstacle, const forecast_obstacle& o, double forecast_time,
                       double obstacle_radius, double heading, double t, double margin, double shorter_than_this,
                       double remaining) {
  const bool turning = t < forecast_time;
  const double omega = turning ? std::abs(o.motion.yaw_rate) : 0.0;
  const vec2 obstacle_velocity{o.motion.speed * std::cos(heading), o.motion.speed * std::sin(heading)};
  const double rho = ego_moves.turn_rate * ego_radius + omega * obstacle_radius;
  const double acceleration = ego_moves.acceleration + omega * o.motion.speed;
  const vec2 relative = ego_moves.velocity - obstacle_velocity;
  for (double h = std::min(longest_translated_step, remaining); h > shorter_than_this; h *= 0.5) {
    const double closest = smallest_signed_distance(ego, obstacle, translation{relative, h}).distance;
    if (closest - margin > h * (rho + 0.5 * acceleration * h)) return h;
  }
  return 0.0;
}

}  // namespace

bool verified_collision_free(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                             std::span<const double> forecast_times, const collision_window& window,
                             double resolution, proof_steps stepping) {
  // The reference's steps, bit for bit; an obstacle whose bounding disc is so far from the ego's
  // that neither its clearance can be ≤ 0 nor its clearance / rate below the step so far is not
  // asked for its distance (its clearance is at least that gap, so it changes neither).
  const double ego_radius = bounding_radius(ego.shape);
  const double largest = largest_speed(ego, u, window.horizon);
  const double ego_rate = largest * (1.0 + std::abs(u.curvature) * ego_radius);
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  // An obstacle's step is the same whichever is visited first (the step taken is the least of
  // theirs), so one whose gap is surely too large to shorten the step is not placed at all: its
  // bounding discs' gap, known at an earlier time, falls no faster than the sum of the reference
  // points' largest speeds.
  struct obstacle_step {
    double rate;         ///< largest rate of the pair's signed distance [m/s]
    double centre_rate;  ///< largest rate of the reference points' distance [m/s]
    double radius;       ///< bounding radius [m]
    pose at;             ///< placement at time `known`
    double gap;          ///< lower bound of its signed distance − margin at time `known` [m]
    double known;        ///< when it was last placed [s]
    double bound;        ///< lower bound of the gap at the current time [m]
  };
  std::vector<obstacle_step> steps(obstacles.size());
  for (std::size_t j = 0; j < obstacles.size(); ++j) {
    const forecast_obstacle& o = obstacles[j];
    steps[j].radius = bounding_radius(o.shape);
    steps[j].rate = ego_rate + o.motion.speed + std::abs(o.motion.yaw_rate) * steps[j].radius;
    steps[j].centre_rate = (largest + o.motion.speed) * (1.0 + 1e-9);
    steps[j].known = -std::numeric_limits<double>::infinity();
  }
  double t = 0.0;
  while (true) {
    const pose ego_pose = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
    const placed_footprint e = place(ego.shape, ego_pose);
    const ego_motion_at ego_moves =
        stepping == proof_steps::translation_bound ? ego_motion(ego, u, ego_pose, t, window, largest) : ego_motion_at{};
    const double remaining = window.duration - t;
    double step = remaining;
    const auto place_at_t = [&](std::size_t j) {
      obstacle_step& s = steps[j];
      s.at = forecast_pose(obstacles[j].motion, forecast_times[j], t);
      const double centres = norm(s.at.position - ego_pose.position);
      const double reach = ego_radius + s.radius + window.margin;
      s.gap = centres - reach - (1e-9 + 1e-12 * (centres + reach));
      s.known = t;
      s.bound = s.gap;
    };
    // A gap that surely leaves the step at `limit`: its obstacle changes nothing.
    const auto surely_apart = [](const obstacle_step& s, double limit) {
      return s.bound > 0.0 && (s.rate <= 0.0 || s.bound / s.rate >= limit);
    };
    // The obstacle that most likely sets the step first: the smallest gap / rate.
    std::size_t first = none;
    double first_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      obstacle_step& s = steps[j];
      if (s.known != t) s.bound = s.gap - s.centre_rate * (t - s.known) - 1e-12;
      if (!surely_apart(s, remaining)) place_at_t(j);
      const double ratio = s.bound <= 0.0 ? -std::numeric_limits<double>::infinity() : s.rate > 0.0 ? s.bound / s.rate : std::numeric_limits<double>::infinity();
      if (first == none || ratio < first_ratio) {
        first = j;
        first_ratio = ratio;
      }
    }
    const auto visit = [&](std::size_t j) {
      obstacle_step& s = steps[j];
      if (surely_apart(s, step)) return true;
      if (s.known != t) {
        place_at_t(j);
        if (surely_apart(s, step)) return true;
      }
      const placed_footprint o = place(obstacles[j].shape, s.at);
      const double clearance = signed_distance(e, o) - window.margin;
      if (clearance <= 0.0) return false;
      if (s.rate > 0.0 && clearance / s.rate < step) {
        const double longer = stepping == proof_steps::speed_bound
                                  ? 0.0
                                  : translated_step(e, ego_moves, ego_radius, o, obstacles[j], forecast_times[j],
                                                    s.radius, s.at.heading, t, window.margin, clearance / s.rate,
                                                    remaining);
        step = std::min(step, std::max(clearance / s.rate, longer));
      }
      return true;
    };
    if (first != none && !visit(first)) return false;
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      if (j != first && !visit(j)) return false;
    }
    if (t >= window.duration) return true;
    if (step < resolution && step < window.duration - t) return false;
    t = std::min(window.duration, t + step);
  }
}

bool verified_collision_free_reference(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                             std::span<const double> forecast_times, const collision_window& window,
                             double resolution, proof_steps stepping) {
  // Largest speed of the ego's reference point along u, and of any of its footprint points.
  const double ego_radius = bounding_radius(ego.shape);
  const double largest = largest_speed(ego, u, window.horizon);
  const double ego_rate = largest * (1.0 + std::abs(u.curvature) * ego_radius);
  double t = 0.0;
  while (true) {
    const pose ego_pose = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
    const placed_footprint e = place(ego.shape, ego_pose);
    const ego_motion_at ego_moves =
        stepping == proof_steps::translation_bound ? ego_motion(ego, u, ego_pose, t, window, largest) : ego_motion_at{};
    const double remaining = window.duration - t;
    double step = remaining;
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      const forecast_obstacle& o = obstacles[j];
      const double radius = bounding_radius(o.shape);
      const double rate = ego_rate + o.motion.speed + std::abs(o.motion.yaw_rate) * radius;
      const pose at = forecast_pose(o.motion, forecast_times[j], t);
      const placed_footprint placed = place(o.shape, at);
      const double clearance = signed_distance(e, placed) - window.margin;
      if (clearance <= 0.0) return false;
      if (rate <= 0.0) continue;
      // The speed bound c / L; the translation bound only where it could give a longer step.
      const double longer = stepping == proof_steps::translation_bound && clearance / rate < step
                                ? translated_step(e, ego_moves, ego_radius, placed, o, forecast_times[j], radius,
                                                  at.heading, t, window.margin, clearance / rate, remaining)
                                : 0.0;
      step = std::min(step, std::max(clearance / rate, longer));
    }
    if (t >= window.duration) return true;
    if (step < resolution && step < window.duration - t) return false;
    t = std::min(window.duration, t + step);
  }
}

namespace {

/// Signed distance − margin [m] of the ego holding `nominal` and the obstacle following its CTRV
/// forecast for the whole window, at time t [s].
double nominal_clearance(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle, double t,
                         const collision_window& window) {
  const pose ego_pose = maneuver_pose(ego.pose, ego.speed, nominal, t, window.horizon, ego.limits.speed_cap);
  const pose obstacle_pose = forecast_pose(obstacle.motion, window.duration, t);
  return signed_distance(place(ego.shape, ego_pose), place(obstacle.shape, obstacle_pose)) - window.margin;
}

}  // namespace

double time_to_collision(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle,
                         const collision_window& window) {
  // How fast their signed distance can change.
  const double rate = largest_point_speed(ego, nominal, window.horizon) + largest_point_speed(obstacle);
  double t = 0.0;
  while (t <= window.duration) {
    const double clearance = nominal_clearance(ego, nominal, obstacle, t, window);
    if (clearance <= 0.0) return t;
    if (!(rate > 0.0)) return no_collision;  // neither moves
    // No contact before t + clearance / rate; a step below the resolution is a contact within
    // rate × resolution, counted as one.
    const double step = clearance / rate * (1.0 - 1e-9);
    if (step < time_to_collision_resolution) return t;
    t += step;
  }
  return no_collision;
}

double time_to_collision_reference(const ego_state& ego, const maneuver& nominal, const forecast_obstacle& obstacle,
                                   const collision_window& window) {
  const auto steps = static_cast<std::size_t>(std::ceil(window.duration / time_to_collision_resolution));
  for (std::size_t k = 0; k <= steps; ++k) {
    const double t = std::min(window.duration, static_cast<double>(k) * time_to_collision_resolution);
    if (nominal_clearance(ego, nominal, obstacle, t, window) <= 0.0) return t;
  }
  return no_collision;
}

}  // namespace mm
