#include "mm/road_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mm {
namespace {

/// What every bound of the fast field is widened by before it decides: the rounding of the
/// distances and spreads it compares [m].
constexpr double rounding_slack = 1e-9;

placed_footprint placed(const ego_state& ego, const placement& p) { return place(ego.shape, p.position, p.direction); }

placement placement_of(const ego_state& ego, const maneuver& u, double t, const collision_window& window) {
  return maneuver_placement(ego.pose, unit_vector(ego.pose.heading), ego.speed, u, t, window.horizon,
                            ego.limits.speed_cap);
}

double clamped(double value, double cap) { return std::max(-cap, std::min(value, cap)); }

double segment_distance(vec2 p, const segment& s) { return std::sqrt(squared_distance_to_segment(p, s.a, s.b)); }

}  // namespace

std::vector<double> road_sample_times(const collision_window& window) {
  std::vector<double> times = sample_times(window.duration, window.time_step);
  times.erase(std::find_if(times.begin(), times.end(), [&](double t) { return !(t < window.horizon); }), times.end());
  times.push_back(window.horizon);
  return times;
}

double road_time_step(const ego_state& ego, const collision_window& window) {
  // As `tunneling_time_step` with an obstacle that stands still and has no width.
  const double speed = speed_after(ego.speed, ego.limits.max_acceleration, window.horizon, ego.limits.speed_cap);
  if (!(speed > 0.0)) return window.duration;
  return smallest_dimension(ego.shape) / speed;
}

bool starts_on_drivable_area(const drivable_area& area, const ego_state& ego) {
  if (!area.contains(ego.pose.position)) return false;
  return boundary_clearance(area.boundary_lines(), place(ego.shape, ego.pose), 1.0) > 0.0;
}

double road_clearance(const drivable_area& area, const ego_state& ego, const maneuver& u,
                      const collision_window& window, double cap) {
  double value = cap;
  for (const double t : road_sample_times(window)) {
    value = std::min(value, boundary_clearance(area.boundary(), placed(ego, placement_of(ego, u, t, window)), cap));
  }
  return clamped(value, cap);
}

clearance_set road_clearances_reference(const drivable_area& area, const ego_state& ego,
                                        std::span<const maneuver> maneuvers, const collision_window& window,
                                        double cap) {
  clearance_set values(maneuvers.size());
  for (std::size_t m = 0; m < maneuvers.size(); ++m) values[m] = road_clearance(area, ego, maneuvers[m], window, cap);
  return values;
}

bool stays_on_drivable_area(const drivable_area& area, const ego_state& ego, const maneuver& u,
                            const collision_window& window, double resolution) {
  const double rate = largest_point_speed(ego, u, window.horizon);
  const auto clearance = [&](double t) {
    return boundary_clearance(area.boundary_lines(), placed(ego, placement_of(ego, u, t, window)),
                              std::numeric_limits<double>::infinity());
  };
  double t = 0.0;
  while (true) {
    const double c = clearance(t);
    if (!(c > 0.0)) return false;
    if (t >= window.horizon) return true;
    const double step = rate > 0.0 ? c / rate : window.horizon;
    if (step < resolution) return false;
    t = std::min(t + step, window.horizon);
  }
}

bool stays_on_drivable_area_reference(const drivable_area& area, const ego_state& ego, const maneuver& u,
                                      const collision_window& window, double resolution) {
  const auto steps = static_cast<std::size_t>(std::floor(window.horizon / resolution));
  for (std::size_t j = 0; j <= steps + 1; ++j) {
    const double t = std::min(static_cast<double>(j) * resolution, window.horizon);
    if (!(boundary_clearance(area.boundary(), placed(ego, placement_of(ego, u, t, window)), 1.0) > 0.0)) return false;
  }
  return true;
}

road_field::road_field(const ego_sweep& sweep, const drivable_area& area, double cap)
    : sweep_(sweep), cap_(cap), collisions_(sweep.sample_count()), values_(sweep.sample_count(), cap),
      exact_(sweep.sample_count(), 0) {
  const ego_state& ego = sweep.ego();
  // Segments farther from the start than the reach by T_h, the footprint's radius and the cap are
  // farther than the cap from every placement: they cannot lower a clamped clearance.
  const double near = sweep.straight_reach().base + bounding_radius(ego.shape) + cap + rounding_slack;
  for (const segment_line& s : area.boundary_lines()) {
    if (segment_distance(ego.pose.position, s.segment_of()) <= near) near_.push_back(s);
  }
  const std::vector<double>& times = sweep.times();
  while (sampled_times_ < times.size() && times[sampled_times_] < sweep.window().horizon) ++sampled_times_;
  if (near_.empty()) return;  // nothing within reach: every sample stays on the road
  footprint_radius_ = bounding_radius(ego.shape) * (1.0 + 1e-12) + rounding_slack;
  footprint_reach_squared_ = footprint_radius_ * footprint_radius_;

  std::vector<std::uint32_t> all(near_.size());
  for (std::uint32_t j = 0; j < all.size(); ++j) all[j] = j;
  std::vector<std::uint32_t> every_time(sampled_times_ + 1);
  for (std::uint32_t r = 0; r < every_time.size(); ++r) every_time[r] = r;
  levels_.reserve(64);
  for (const std::uint32_t root : sweep.roots()) decide(root, every_time, all, 0);
  collisions_.for_each([&](std::size_t m) { values_[m] = -cap_; });
}

placement road_field::at(std::size_t r, std::size_t m) const {
  return r < sampled_times_ ? sweep_.at(r, m) : sweep_.placement_at(m, sweep_.window().horizon);
}

double road_field::spread(std::uint32_t b, std::size_t r) const {
  return r < sampled_times_ ? sweep_.block_spread(sweep_.block_of(b), r) : sweep_.straight_spread(b).base;
}

void road_field::decide(std::uint32_t b, std::span<const std::uint32_t> times, std::span<const std::uint32_t> segments,
                        std::size_t depth) {
  const ego_sweep::block& block = sweep_.block_of(b);
  const std::vector<std::uint32_t>& order = sweep_.order();
  const ego_state& ego = sweep_.ego();
  if (block.end - block.begin == 1) {
    // One sample: off the road at the first time its footprint reaches the boundary. A segment whose
    // lower bound is positive cannot be reached then.
    for (const std::uint32_t r : times) {
      ++bound_checks_;
      const placement p = at(r, block.centre);
      const placed_footprint f = placed(ego, p);
      for (const std::uint32_t j : segments) {
        const segment_line& s = near_[j];
        if (line_distance_bound(f, s) > rounding_slack) continue;
        if (squared_distance_to_segment(p.position, s.a, s.b) > footprint_reach_squared_) continue;
        if (!(signed_distance(f, s) > 0.0)) {
          collisions_.set(block.centre);
          return;
        }
      }
    }
    return;
  }
  if (levels_.size() <= depth) levels_.resize(depth + 1);
  level& mine = levels_[depth];
  mine.times.clear();
  mine.distances.resize(times.size() * segments.size());
  mine.reach.clear();
  // Every point of a sample's footprint lies within the spread of the centre's: its signed distance
  // to each segment within the spread of the centre's. A time at which the centre is farther than
  // the spread from every segment is decided clear for the whole block; one at which it is across
  // by more than the spread puts every sample of the block off the road.
  for (std::size_t t = 0; t < times.size(); ++t) {
    const std::uint32_t r = times[t];
    ++bound_checks_;
    const placed_footprint f = placed(ego, at(r, block.centre));
    double* d = mine.distances.data() + mine.times.size() * segments.size();
    double nearest = cap_;
    for (std::size_t j = 0; j < segments.size(); ++j) {
      d[j] = signed_distance(f, near_[segments[j]]);
      nearest = std::min(nearest, d[j]);
    }
    const double sigma = spread(b, r) + rounding_slack * (1.0 + std::abs(nearest));
    if (nearest - sigma > 0.0) continue;
    if (nearest + sigma <= 0.0) {
      for (std::uint32_t p = block.begin; p < block.end; ++p) collisions_.set(order[p]);
      return;
    }
    mine.times.push_back(r);
    mine.reach.push_back(nearest + 2.0 * sigma);
  }
  if (mine.times.empty()) return;
  // A segment more than twice the spread farther than the nearest, at every time left, cannot be
  // the nearest of any sample of the block then: the halves do not ask it.
  mine.segments.clear();
  for (std::size_t j = 0; j < segments.size(); ++j) {
    for (std::size_t t = 0; t < mine.times.size(); ++t) {
      if (mine.distances[t * segments.size() + j] <= mine.reach[t]) {
        mine.segments.push_back(segments[j]);
        break;
      }
    }
  }
  decide(b + 1, levels_[depth].times, levels_[depth].segments, depth + 1);
  decide(block.second, levels_[depth].times, levels_[depth].segments, depth + 1);
}

double road_field::exact(std::size_t m) {
  if (exact_[m] != 0) return values_[m];
  const ego_state& ego = sweep_.ego();
  // The smallest so far caps the next time's: `boundary_clearance` is min(cap, …), so the minimum is
  // the same, and segments that cannot lower it are not asked. The latest time first: a maneuver that
  // turns toward an edge is nearest it at T_h, and the earlier times then ask few segments.
  // Only the segments within the cap and the footprint's radius of the box of the sample's reference
  // points over the road times can be nearer than the cap at one of them.
  vec2 lo = at(0, m).position;
  vec2 hi = lo;
  for (std::size_t r = 1; r <= sampled_times_; ++r) {
    const vec2 q = at(r, m).position;
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
  }
  const double reach = cap_ + footprint_radius_;
  candidates_.clear();
  for (const segment_line& s : near_) {
    const double gap_x = std::max({std::min(s.a.x, s.b.x) - hi.x, lo.x - std::max(s.a.x, s.b.x), 0.0});
    const double gap_y = std::max({std::min(s.a.y, s.b.y) - hi.y, lo.y - std::max(s.a.y, s.b.y), 0.0});
    if (gap_x * gap_x + gap_y * gap_y <= reach * reach) candidates_.push_back(s);
  }
  double value = cap_;
  for (std::size_t r = sampled_times_ + 1; r-- > 0;) value = boundary_clearance(candidates_, placed(ego, at(r, m)), value);
  values_[m] = clamped(value, cap_);
  exact_[m] = 1;
  return values_[m];
}

}  // namespace mm
