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

/// The footprint's bounding radius about its reference point, rounded up [m].
double rounded_up_radius(const footprint& shape) { return bounding_radius(shape) * (1.0 + 1e-12) + rounding_slack; }

/// The boundary segments within `reach` [m] of `point`.
std::vector<segment_line> segments_near(const drivable_area& area, vec2 point, double reach) {
  std::vector<segment_line> near;
  for (const segment_line& s : area.boundary_lines()) {
    if (std::sqrt(squared_distance_to_segment(point, s.a, s.b)) <= reach) near.push_back(s);
  }
  return near;
}

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
  // Every footprint of the maneuver within T_h lies within its arc length by T_h and the footprint's
  // radius of the start: a segment more than `apart` [m] farther than that from the start is farther
  // than `apart` from each. The segments nearer give the clearance exactly where it is below `apart`;
  // elsewhere every segment is asked.
  constexpr double apart = 5.0;
  const std::vector<segment_line> near = segments_near(
      area, ego.pose.position,
      travelled_distance(ego.speed, u.acceleration, window.horizon, ego.limits.speed_cap) +
          rounded_up_radius(ego.shape) + apart);
  const auto clearance = [&](double t) {
    const placed_footprint f = placed(ego, placement_of(ego, u, t, window));
    const double value = boundary_clearance(near, f, std::numeric_limits<double>::infinity());
    if (value < apart) return value;
    return boundary_clearance(area.boundary_lines(), f, std::numeric_limits<double>::infinity());
  };
  double t = 0.0;
  while (true) {
    const double c = clearance(t);
    if (!(c > 0.0)) return false;
    if (t >= window.horizon) return true;
    const double step = rate > 0.0 ? c / rate : window.horizon;
    if (step < resolution && step < window.horizon - t) return false;
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
  near_ = segments_near(area, ego.pose.position, sweep.straight_reach().base + rounded_up_radius(ego.shape) + cap);
  const std::vector<double>& times = sweep.times();
  while (sampled_times_ < times.size() && times[sampled_times_] < sweep.window().horizon) ++sampled_times_;
  if (near_.empty()) return;  // nothing within reach: every sample stays on the road
  footprint_radius_ = rounded_up_radius(ego.shape);

  decide();
  collisions_.for_each([&](std::size_t m) { values_[m] = -cap_; });
}

placement road_field::at(std::size_t r, std::size_t m) const {
  return r < sampled_times_ ? sweep_.at(r, m) : sweep_.placement_at(m, sweep_.window().horizon);
}

namespace {

/// The index of `value` in `values`, appended when new; `guess` is tried first (the samples come in
/// rows and columns, so the previous sample's neighbour usually matches).
std::uint32_t index_of(std::vector<double>& values, double value, std::uint32_t guess) {
  for (const std::uint32_t g : {guess, guess + 1}) {
    if (g < values.size() && values[g] == value) return g;
  }
  for (std::uint32_t i = 0; i < values.size(); ++i) {
    if (values[i] == value) return i;
  }
  values.push_back(value);
  return static_cast<std::uint32_t>(values.size() - 1);
}

}  // namespace

void road_field::decide() {
  const maneuver_samples& samples = sweep_.samples();
  const ego_state& ego = sweep_.ego();
  const std::vector<double>& times = sweep_.times();
  const std::size_t road_times = sampled_times_ + 1;
  // The samples' rows (accelerations) and columns (curvatures), and each row's arc length at each
  // road time: before T_h a sample's placement is the arc placement of its curvature at that arc
  // length (`arc_placement`).
  std::vector<double> accelerations;
  std::vector<double> curvatures;
  row_of_.resize(samples.size());
  column_of_.resize(samples.size());
  std::uint32_t row = 0;
  std::uint32_t column = 0;
  for (std::size_t m = 0; m < samples.size(); ++m) {
    row = index_of(accelerations, samples.maneuvers[m].acceleration, row);
    column = index_of(curvatures, samples.maneuvers[m].curvature, column);
    row_of_[m] = row;
    column_of_[m] = column;
  }
  arc_.resize(accelerations.size() * road_times);
  for (std::size_t i = 0; i < accelerations.size(); ++i) {
    for (std::size_t r = 0; r < road_times; ++r) {
      const double t = r < sampled_times_ ? times[r] : sweep_.window().horizon;
      arc_[i * road_times + r] = travelled_distance(ego.speed, accelerations[i], t, ego.limits.speed_cap);
    }
  }
  lipschitz_.resize(curvatures.size());
  for (std::size_t c = 0; c < curvatures.size(); ++c) lipschitz_[c] = 1.0 + std::abs(curvatures[c]) * footprint_radius_;
  evaluations_.resize(curvatures.size());
  for (std::vector<evaluation>& e : evaluations_) e.clear();
  // Per column, the stretches of arc length proven clear of the boundary or across it, disjoint and
  // in order. A clearance c at arc length s proves |c|/L either side of s, L = 1 + |κ| R: moving
  // along the arc by Δs moves no point of the footprint farther than L·|Δs|.
  proofs_.resize(curvatures.size());
  for (std::vector<proven>& p : proofs_) p.clear();
  for (std::size_t m = 0; m < samples.size(); ++m) {
    std::vector<proven>& proofs = proofs_[column_of_[m]];
    const double lipschitz = lipschitz_[column_of_[m]];
    const double* s_at = arc_.data() + row_of_[m] * road_times;
    for (std::size_t r = 0; r < road_times; ++r) {
      const double s = s_at[r];
      auto next = std::upper_bound(proofs.begin(), proofs.end(), s, [](double v, const proven& p) { return v < p.lo; });
      if (next != proofs.begin() && s <= std::prev(next)->hi) {
        if (!std::prev(next)->off) continue;
        collisions_.set(m);
        break;
      }
      ++bound_checks_;
      const double c = boundary_clearance(near_, placed(ego, at(r, m)), cap_);
      std::vector<evaluation>& found = evaluations_[column_of_[m]];
      found.insert(std::upper_bound(found.begin(), found.end(), s, before), {s, c});
      const bool off = !(c > 0.0);
      const double width = (std::abs(c) - rounding_slack * (1.0 + std::abs(c))) / lipschitz * (1.0 - 1e-12);
      if (width > 0.0) add_proof(proofs, {s - width, s + width, off});
      if (off) {
        collisions_.set(m);
        break;
      }
    }
  }
}

double road_field::lower_bound_at(const std::vector<evaluation>& found, double s, double lipschitz) {
  // The clearance is L-Lipschitz in the arc length (see `decide`): each evaluation bounds it below;
  // the nearest on either side bound it most, up to where they are capped.
  const auto next = std::upper_bound(found.begin(), found.end(), s, before);
  double bound = -std::numeric_limits<double>::infinity();
  if (next != found.end()) bound = next->clearance - lipschitz * (next->arc_length - s);
  if (next != found.begin()) {
    const evaluation& before = *std::prev(next);
    bound = std::max(bound, before.clearance - lipschitz * (s - before.arc_length));
  }
  return bound;
}

void road_field::add_proof(std::vector<proven>& proofs, proven p) {
  // Proofs of the two kinds never overlap (a stretch is not both clear and across); one of the same
  // kind that overlaps is merged.
  auto at_or_after = std::lower_bound(proofs.begin(), proofs.end(), p.lo, [](const proven& q, double v) { return q.lo < v; });
  if (at_or_after != proofs.begin() && std::prev(at_or_after)->off == p.off && std::prev(at_or_after)->hi >= p.lo) {
    --at_or_after;
    p.lo = at_or_after->lo;
    p.hi = std::max(p.hi, at_or_after->hi);
    at_or_after = proofs.erase(at_or_after);
  }
  while (at_or_after != proofs.end() && at_or_after->off == p.off && at_or_after->lo <= p.hi) {
    p.hi = std::max(p.hi, at_or_after->hi);
    at_or_after = proofs.erase(at_or_after);
  }
  proofs.insert(at_or_after, p);
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
  // A time at which a clearance `decide` found nearby on the sample's arc bounds the clearance above
  // the smallest so far cannot lower it, and is not asked.
  const std::vector<evaluation>* found = near_.empty() ? nullptr : &evaluations_[column_of_[m]];
  const double lipschitz = near_.empty() ? 1.0 : lipschitz_[column_of_[m]];
  double value = cap_;
  for (std::size_t r = sampled_times_ + 1; r-- > 0;) {
    if (found != nullptr) {
      const double s = arc_[row_of_[m] * (sampled_times_ + 1) + r];
      if (lower_bound_at(*found, s, lipschitz) > value + rounding_slack * (1.0 + std::abs(value))) continue;
    }
    value = boundary_clearance(candidates_, placed(ego, at(r, m)), value);
  }
  values_[m] = clamped(value, cap_);
  exact_[m] = 1;
  return values_[m];
}

}  // namespace mm
