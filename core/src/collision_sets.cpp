#include "mm/collision_sets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mm {

double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window) {
  const pose p = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
  return signed_distance(place(ego.shape, p), place(obstacle.shape, forecast_pose(obstacle.motion, tau, t))) -
         window.margin;
}

ego_sweep::ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window)
    : ego_(ego),
      samples_(samples),
      window_(window),
      sample_count_(samples.size()),
      times_(sample_times(window.duration, window.time_step)) {
  poses_.reserve(times_.size() * sample_count_);
  reach_centre_.reserve(times_.size());
  reach_radius_.reserve(times_.size());
  for (const double t : times_) {
    vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    vec2 hi = -lo;
    const std::size_t first = poses_.size();
    for (const maneuver& u : samples.maneuvers) {
      const pose p = maneuver_pose(ego.pose, ego.speed, u, t, window.horizon, ego.limits.speed_cap);
      poses_.push_back(p);
      directions_.push_back({std::cos(p.heading), std::sin(p.heading)});
      lo = {std::min(lo.x, p.position.x), std::min(lo.y, p.position.y)};
      hi = {std::max(hi.x, p.position.x), std::max(hi.y, p.position.y)};
    }
    const vec2 centre = 0.5 * (lo + hi);
    double radius = 0.0;
    for (std::size_t m = first; m < poses_.size(); ++m) {
      radius = std::max(radius, norm(poses_[m].position - centre));
    }
    reach_centre_.push_back(centre);
    reach_radius_.push_back(radius);
  }
  largest_speed_ = speed_after(ego.speed, ego.limits.max_acceleration, window.horizon, ego.limits.speed_cap);
  largest_point_speed_ = largest_speed_ * (1.0 + max_curvature(ego.speed, ego.limits) * bounding_radius(ego.shape));
}

namespace {

/// Running minimum of every sample's clearance, and the first time index at which each sample
/// could lower it.
struct clearance_walk {
  std::vector<running_minimum> minimum;
  std::vector<std::size_t> next;
};

/// What stays the same while walking one obstacle through the sweep.
struct walk_constants {
  double reach;         ///< bounding radii of ego and obstacle [m]
  double margin;        ///< [m]
  double cap;           ///< [m]
  double centre_rate;   ///< Lipschitz constant of the reference points' distance [m/s]
  double distance_rate; ///< Lipschitz constant of the signed distance [m/s]
  double time_step;     ///< [s]
};

/// First time index after k at which a quantity `gap` above the target, changing at most at
/// `rate`, could reach the target.
std::size_t first_possible(std::size_t k, double gap, double rate, double time_step) {
  if (rate <= 0.0) return std::numeric_limits<std::size_t>::max();
  const double steps = gap * (1.0 - 1e-9) / (rate * time_step);
  if (steps >= 1e9) return std::numeric_limits<std::size_t>::max();
  return k + static_cast<std::size_t>(steps) + 1;
}

/// Advances `walk` over time index k, with the obstacle at `where`.
void advance(const ego_sweep& sweep, const forecast_obstacle& obstacle, const pose& where, const walk_constants& w,
             std::size_t k, clearance_walk& walk) {
  const vec2 o = where.position;
  if (norm(o - sweep.reach_centre(k)) - sweep.reach_radius(k) - w.reach - w.margin >= w.cap) return;
  const placed_footprint obstacle_footprint = place(obstacle.shape, where);
  for (std::size_t m = 0; m < sweep.sample_count(); ++m) {
    if (walk.next[m] > k) continue;
    running_minimum& r = walk.minimum[m];
    const double known = std::min(r.value, w.cap);
    if (known <= -w.cap) {
      walk.next[m] = std::numeric_limits<std::size_t>::max();
      continue;
    }
    const pose& p = sweep.at(k, m);
    const double bound = norm(p.position - o) - w.reach - w.margin;
    if (bound >= known) {
      walk.next[m] = first_possible(k, bound - known, w.centre_rate, w.time_step);
      continue;
    }
    const double d = signed_distance(place(sweep.ego().shape, p.position, sweep.direction(k, m)), obstacle_footprint) - w.margin;
    r.update(d, k);
    walk.next[m] = first_possible(k, d - std::min(r.value, w.cap), w.distance_rate, w.time_step);
  }
}

}  // namespace

std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap) {
  const std::vector<double>& times = sweep.times();
  const motion_estimate& motion = obstacle.motion;
  const double obstacle_radius = bounding_radius(obstacle.shape);
  const double distance_rate = sweep.largest_point_speed() + motion.speed + std::abs(motion.yaw_rate) * obstacle_radius;
  // Minima up to half a step's change above the cap can still refine to below it: walk exactly to there.
  const double walk_cap = cap + distance_rate * sweep.window().time_step / 2.0;
  const walk_constants w{bounding_radius(sweep.ego().shape) + obstacle_radius,
                         sweep.window().margin,
                         walk_cap,
                         sweep.largest_speed() + motion.speed,
                         distance_rate,
                         sweep.window().time_step};
  const ego_state& ego = sweep.ego();
  const collision_window& window = sweep.window();
  const maneuver_samples& samples = sweep.samples();
  std::vector<clearance_set> result;
  result.reserve(forecast_times.size());
  // The walk over the times t ≤ τ, where every forecast agrees; [0, shared_until) is done.
  clearance_walk shared{std::vector<running_minimum>(sweep.sample_count()),
                        std::vector<std::size_t>(sweep.sample_count(), 0)};
  std::size_t shared_until = 0;
  for (const double tau : forecast_times) {
    for (; shared_until < times.size() && times[shared_until] <= tau; ++shared_until) {
      advance(sweep, obstacle, forecast_pose(motion, tau, times[shared_until]), w, shared_until, shared);
    }
    clearance_walk walk = shared;
    for (std::size_t k = shared_until; k < times.size(); ++k) {
      advance(sweep, obstacle, forecast_pose(motion, tau, times[k]), w, k, walk);
    }
    clearance_set clearance(sweep.sample_count());
    for (std::size_t m = 0; m < sweep.sample_count(); ++m) {
      const running_minimum& r = walk.minimum[m];
      double c = r.value;
      if (c > -walk_cap && c < walk_cap) {
        c = refined_minimum(times, r.argmin, [&](double t) { return clearance_at(ego, samples.maneuvers[m], obstacle, tau, t, window); },
                            r.value);
      }
      clearance[m] = std::clamp(c, -cap, cap);
    }
    result.push_back(std::move(clearance));
  }
  return result;
}

std::vector<clearance_set> clearances_reference(const ego_state& ego, const maneuver_samples& samples,
                                                const forecast_obstacle& obstacle,
                                                std::span<const double> forecast_times,
                                                const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  std::vector<clearance_set> result;
  for (const double tau : forecast_times) {
    clearance_set clearance(samples.size());
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const auto at = [&](double t) { return clearance_at(ego, samples.maneuvers[m], obstacle, tau, t, window); };
      running_minimum r;
      for (std::size_t k = 0; k < times.size(); ++k) r.update(at(times[k]), k);
      clearance[m] = refined_minimum(times, r.argmin, at, r.value);
    }
    result.push_back(std::move(clearance));
  }
  return result;
}

std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window, double proof_resolution) {
  std::vector<sample_mask> sets;
  for (const double tau : forecast_times) {
    sample_mask set(samples.size());
    const std::array<double, 1> taus{tau};
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (!verified_collision_free(ego, samples.maneuvers[m], std::span(&obstacle, 1), taus, window, proof_resolution)) {
        set.set(m);
      }
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

}  // namespace mm
