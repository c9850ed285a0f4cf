#include "mm/collision_sets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mm {

ego_sweep::ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window)
    : ego_(ego),
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
}

namespace {

/// Adds to `mask` the samples whose footprint at time index k overlaps the obstacle at `where`.
void add_hits(const ego_sweep& sweep, const forecast_obstacle& obstacle, const pose& where,
              double reach, std::size_t k, sample_mask& mask) {
  const vec2 o = where.position;
  const double far = sweep.reach_radius(k) + reach;
  if (squared_norm(o - sweep.reach_centre(k)) >= far * far) return;
  const placed_footprint obstacle_footprint = place(obstacle.shape, where);
  const double reach2 = reach * reach;
  for (std::size_t m = 0; m < sweep.sample_count(); ++m) {
    if (mask.test(m)) continue;
    const pose& p = sweep.at(k, m);
    if (squared_norm(p.position - o) >= reach2) continue;
    if (overlaps(place(sweep.ego().shape, p), obstacle_footprint, sweep.window().margin)) mask.set(m);
  }
}

}  // namespace

std::vector<sample_mask> collision_sets(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                        std::span<const double> forecast_times) {
  const std::vector<double>& times = sweep.times();
  const double reach = bounding_radius(sweep.ego().shape) + bounding_radius(obstacle.shape) + sweep.window().margin;
  std::vector<sample_mask> sets;
  sets.reserve(forecast_times.size());
  sample_mask shared(sweep.sample_count());  // hits at times t ≤ τ, where every forecast agrees
  std::size_t shared_until = 0;              // time indices [0, shared_until) are in `shared`
  for (const double tau : forecast_times) {
    for (; shared_until < times.size() && times[shared_until] <= tau; ++shared_until) {
      add_hits(sweep, obstacle, forecast_pose(obstacle.motion, tau, times[shared_until]), reach,
               shared_until, shared);
    }
    sample_mask set = shared;
    for (std::size_t k = shared_until; k < times.size(); ++k) {
      add_hits(sweep, obstacle, forecast_pose(obstacle.motion, tau, times[k]), reach, k, set);
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window) {
  std::vector<sample_mask> sets;
  for (const double tau : forecast_times) {
    sample_mask set(samples.size());
    const std::array<double, 1> taus{tau};
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (maneuver_collides(ego, samples.maneuvers[m], std::span(&obstacle, 1), taus, window)) set.set(m);
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

}  // namespace mm
