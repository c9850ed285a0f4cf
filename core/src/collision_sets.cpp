#include "mm/collision_sets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <variant>

namespace mm {

double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window) {
  const placement e = maneuver_placement(ego.pose, unit_vector(ego.pose.heading), ego.speed, u, t, window.horizon,
                                         ego.limits.speed_cap);
  return signed_distance(place(ego.shape, e.position, e.direction),
                         place(obstacle.shape, forecast_pose(obstacle.motion, tau, t))) -
         window.margin;
}

ego_sweep::ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window)
    : ego_(ego),
      samples_(samples),
      window_(window),
      sample_count_(samples.size()),
      times_(sample_times(window.duration, window.time_step)),
      start_rotation_(unit_vector(ego.pose.heading)) {
  const double horizon = window.horizon;
  const double cap = ego.limits.speed_cap;
  straight_.reserve(sample_count_);
  for (const maneuver& u : samples.maneuvers) {
    // maneuver_local_placement's values for t > T_h, in its order of operations.
    const placement end = maneuver_local_placement(ego.speed, u, horizon, horizon, cap);
    straight_.push_back({end.position, end.direction, speed_after(ego.speed, u.acceleration, horizon, cap),
                         rotated(end.direction, start_rotation_.x, start_rotation_.y)});
  }
  for (const maneuver& u : samples.maneuvers) {
    sample_speed_.push_back(mm::largest_speed(ego, u, horizon));
    sample_point_speed_.push_back(mm::largest_point_speed(ego, u, horizon));
  }
  known_.assign(times_.size() * sample_count_, 0);
  placements_ = std::make_unique_for_overwrite<stored[]>(times_.size() * sample_count_);
  largest_speed_ = speed_after(ego.speed, ego.limits.max_acceleration, horizon, cap);
  largest_point_speed_ = largest_speed_ * (1.0 + max_curvature(ego.speed, ego.limits) * bounding_radius(ego.shape));
  // Every sample's reference point lies within its arc length of the start, and no sample travels
  // farther than the one at a_max.
  reach_radius_.reserve(times_.size());
  for (const double t : times_) {
    double travel = travelled_distance(ego.speed, ego.limits.max_acceleration, std::min(t, horizon), cap);
    if (t > horizon) travel += largest_speed_ * (t - horizon);
    reach_radius_.push_back(travel * (1.0 + 1e-12) + 1e-9);
  }
}

ego_sweep::placement ego_sweep::placement_at(std::size_t m, double t) const {
  const vec2 rotation = start_rotation_;
  if (t > window_.horizon) {
    const straight_part& part = straight_[m];
    const vec2 local = part.local + (part.speed * (t - window_.horizon)) * part.along;
    return {ego_.pose.position + rotated(local, rotation.x, rotation.y), part.direction};
  }
  return maneuver_placement(ego_.pose, rotation, ego_.speed, samples_.maneuvers[m], t, window_.horizon,
                            ego_.limits.speed_cap);
}

void ego_sweep::fill(std::size_t k, std::size_t m) const {
  const placement p = placement_at(m, times_[k]);
  const std::size_t index = k * sample_count_ + m;
  placements_[index] = {p.position.x, p.position.y, p.direction.x, p.direction.y};
  known_[index] = 1;
}

double largest_speed(const ego_state& ego, const maneuver& u, double horizon) {
  const double cap = ego.limits.speed_cap;
  return std::max(std::min(ego.speed, cap), speed_after(ego.speed, u.acceleration, horizon, cap));
}

double largest_point_speed(const ego_state& ego, const maneuver& u, double horizon) {
  return largest_speed(ego, u, horizon) * (1.0 + std::abs(u.curvature) * bounding_radius(ego.shape));
}

double largest_point_speed(const forecast_obstacle& obstacle) {
  return obstacle.motion.speed + std::abs(obstacle.motion.yaw_rate) * bounding_radius(obstacle.shape);
}

double refinement_threshold(double rate, double time_step) { return 0.5 * rate * time_step * (1.0 + 1e-9) + 1e-12; }

namespace {

/// A lower bound computed in floating point can exceed what it bounds by a few units in the last
/// place where the two are equal in exact arithmetic (the face separation of parallel faces is
/// their distance). Every bound that lets a walk skip a time is lowered by this [m], so that a time
/// is skipped only when it provably cannot matter, to the last bit.
constexpr double rounding_slack = 1e-12;

/// First time index after k at which a quantity `gap` above the target, changing at most at
/// `rate`, could reach the target (k + 1 when it is not above).
std::size_t first_possible(std::size_t k, double gap, double rate, double time_step) {
  if (!(gap > 0.0)) return k + 1;
  if (rate <= 0.0) return std::numeric_limits<std::size_t>::max();
  const double steps = gap * (1.0 - 1e-9) / (rate * time_step);
  if (steps >= 1e9) return std::numeric_limits<std::size_t>::max();
  return k + static_cast<std::size_t>(steps) + 1;
}

}  // namespace

struct clearance_field::sign_state {
  std::size_t next = 0;   ///< first time index at which it can come within θ
  bool low = false;       ///< came within θ at a sample time
  bool negative = false;  ///< touched at a sample time, or a dip refined to ≤ 0
  double minimum = std::numeric_limits<double>::infinity();  ///< smallest value looked at
  dips low_dips;
};

/// The samples a sign walk follows, with their states, and per sample time the list of those to be
/// looked at then: each sample waits in one list, that of the first time at which it can come
/// within θ (none once it is known to collide or can no longer come within θ).
struct clearance_field::sign_walk {
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> sample;  ///< [j]: the sample whose state is state[j]
  std::vector<sign_state> state;      ///< [j]
  std::vector<std::uint32_t> link;    ///< [j]: the next in the same list
  std::vector<std::uint32_t> head;    ///< [k]: the first waiting for time index k

  explicit sign_walk(std::size_t times) : head(times, none) {}
  void clear() {
    sample.clear();
    state.clear();
    link.clear();
    std::fill(head.begin(), head.end(), none);
  }
  /// Starts following sample m in `s`; returns its index j.
  std::uint32_t follow(std::size_t m, const sign_state& s) {
    sample.push_back(static_cast<std::uint32_t>(m));
    state.push_back(s);
    link.push_back(none);
    return static_cast<std::uint32_t>(sample.size() - 1);
  }
  /// State j waits for time index k (k past the last time: it is done).
  void wait(std::size_t k, std::uint32_t j) {
    if (k >= head.size()) return;
    link[j] = head[k];
    head[k] = j;
  }
  /// Empties the list of time index k and returns its first state.
  std::uint32_t take(std::size_t k) {
    const std::uint32_t j = head[k];
    head[k] = none;
    return j;
  }
};

clearance_field::dip clearance_field::visit(dips& d, std::size_t k, bool looked, double value, double theta) {
  dip confirmed;
  if (d.candidate != dips::no_index) {
    // The candidate is a local minimum unless the time after it is lower; a time not looked at is > θ.
    if (d.candidate + 1 < k || !looked || value >= d.candidate_value) confirmed = {d.candidate, d.candidate_value};
    d.candidate = dips::no_index;
  }
  if (looked) {
    if (value <= theta && (d.last == dips::no_index || d.last + 1 != k || value <= d.last_value)) {
      d.candidate = k;
      d.candidate_value = value;
    }
    d.last = k;
    d.last_value = value;
  }
  return confirmed;
}

clearance_field::clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                 std::span<const double> forecast_times, double cap)
    : sweep_(sweep), obstacle_(obstacle), taus_(forecast_times.begin(), forecast_times.end()), cap_(cap) {
  const std::vector<double>& times = sweep.times();
  const motion_estimate& motion = obstacle.motion;
  const collision_window& window = sweep.window();
  const double step = window.time_step;
  const double obstacle_radius = bounding_radius(obstacle.shape);
  obstacle_turn_speed_ = largest_point_speed(obstacle);
  distance_rate_ = sweep.largest_point_speed() + obstacle_turn_speed_;
  // Minima up to half a step's change above the cap can still refine to below it: walk exactly to there.
  walk_cap_ = cap + distance_rate_ * step / 2.0;
  reach_ = bounding_radius(sweep.ego().shape) + obstacle_radius + rounding_slack;
  centre_rate_ = sweep.largest_speed() + motion.speed;
  if (const auto* ego_shape = std::get_if<rectangle>(&sweep.ego().shape)) {
    ego_half_ = {ego_shape->length / 2.0, ego_shape->width / 2.0};
    if (const auto* r = std::get_if<rectangle>(&obstacle.shape)) {
      shapes_ = shape_pair::rectangles;
      obstacle_half_ = {r->length / 2.0, r->width / 2.0};
    } else if (const auto* d = std::get_if<disc>(&obstacle.shape)) {
      shapes_ = shape_pair::rectangle_disc;
      obstacle_radius_ = d->radius;
    }
  }
  const bool rectangles = shapes_ == shape_pair::rectangles;
  const std::size_t samples = sweep.sample_count();
  const std::size_t count = taus_.size();

  // The obstacle's placements: the CTRV part shared by every τ ≥ t, then per τ the straight part.
  // Without a turn every forecast time gives the same forecast: all times are shared.
  independent_ = motion.yaw_rate == 0.0;
  const double last_tau = count == 0 ? 0.0 : taus_.back();
  for (std::size_t k = 0; k < times.size() && (independent_ || times[k] <= last_tau); ++k) {
    const pose p = forecast_pose(motion, times[k], times[k]);
    turning_.push_back({p.position, unit_vector(p.heading)});
  }
  for (const double tau : taus_) {
    const pose p = forecast_pose(motion, tau, tau);
    turn_end_.push_back({p.position, unit_vector(p.heading)});
    std::size_t k = 0;
    while (k < times.size() && (independent_ || times[k] <= tau)) ++k;
    first_straight_.push_back(k);
  }
  const std::size_t slots = independent_ ? std::min<std::size_t>(count, 1) : count;
  sets_.assign(slots, clearance_set(samples, cap));
  below_cap_.assign(slots, 0);
  colliding_.assign(slots, 0);
  floor_.assign(slots, {});
  exact_.assign(slots, std::vector<std::uint8_t>(samples, 0));
  prefix_.assign(samples, prefix_walk{});
  refined_.assign(samples, {});

  // A sampled minimum above this refines to a positive clearance: between samples the signed
  // distance can fall by at most L·step/2 below the nearest sample.
  const double threshold = refinement_threshold(distance_rate_, step);
  const double margin = window.margin;
  const vec2 start = sweep.reach_centre(0);
  // [m]: the time index at which sample m touched the obstacle under the last forecast time that
  // made it touch (none yet).
  std::vector<std::uint32_t> contact(samples, sign_walk::none);
  bool near = false;
  // Refines a confirmed dip of sample m under forecast time i: one at or below 0 makes it negative.
  const auto settle = [&](sign_state& state, std::size_t i, std::size_t m, const dip& d) {
    if (d.at == dips::no_index) return;
    const double value = refined_at(i, m, d.at, d.value);
    state.low_dips.refined = std::min(state.low_dips.refined, value);
    if (value <= 0.0) state.negative = true;
  };
  // Looks at the samples waiting for time index k, the obstacle placed at `o`; dips confirmed here
  // are refined under forecast time i (at times shared by every τ when k is).
  const auto advance = [&](std::size_t k, const obstacle_at& o, sign_walk& walk, std::size_t i) {
    std::uint32_t j = walk.take(k);
    const double disc_gap = norm(o.position - start) - sweep.reach_radius(k) - reach_ - margin;
    if (disc_gap < walk_cap_) near = true;
    if (disc_gap > threshold) {
      // No sample can be within θ now: they all wait for the next time.
      while (j != sign_walk::none) {
        const std::uint32_t after = walk.link[j];
        walk.wait(k + 1, j);
        j = after;
      }
      return;
    }
    const placed_footprint obstacle_footprint =
        shapes_ == shape_pair::general ? place(obstacle_.shape, o.position, o.direction) : placed_footprint{};
    const placed_rectangle obstacle_rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
    while (j != sign_walk::none) {
      const std::uint32_t after = walk.link[j];
      const std::size_t m = walk.sample[j];
      sign_state& state = walk.state[j];
      if (state.negative) {
        // Shown to touch at a later time before the walk came here (`touches` below).
        j = after;
        continue;
      }
      // Every time at which the clearance can be ≤ θ is looked at: a skipped one is > θ.
      const double rate = distance_rate(m);
      const double theta = sample_threshold(m);
      const ego_sweep::placement p = sweep.at(k, m);
      ++work_.bound_checks;
      const double bound = norm(p.position - o.position) - reach_ - margin;
      double d = 0.0;
      bool looked = false;
      if (bound > theta) {
        state.next = first_possible(k, bound - theta, centre_rate(m), step);
      } else if (rectangles) {
        // The separation along the face normals bounds the signed distance from below (it is the
        // signed distance when they overlap) and changes no faster than it.
        const placed_rectangle ego_rectangle{p.position, p.direction, ego_half_.x, ego_half_.y};
        const double face = face_separation(ego_rectangle, obstacle_rectangle);
        const double separation = face - margin;
        if (separation - rounding_slack > theta) {
          state.next = first_possible(k, separation - rounding_slack - theta, rate, step);
        } else if (face <= 0.0) {
          state.negative = true;
          contact[m] = static_cast<std::uint32_t>(k);
        } else {
          // Apart (separation > 0): the signed distance is the corner distance.
          d = corner_distance(ego_rectangle, obstacle_rectangle) - margin;
          looked = true;
        }
      } else if (shapes_ == shape_pair::general) {
        // The obstacle's footprint is placed once per time, not once per sample.
        d = signed_distance(place(sweep.ego().shape, p.position, p.direction), obstacle_footprint) - margin;
        looked = true;
      } else {
        d = distance(p.position, p.direction, o) - margin;
        looked = true;
      }
      if (looked) {
        ++work_.distance_evaluations;
        if (d <= 0.0) {
          state.negative = true;
          contact[m] = static_cast<std::uint32_t>(k);
        } else {
          state.minimum = std::min(state.minimum, d);
          if (d <= theta) state.low = true;
          state.next = first_possible(k, d - theta, rate, step);
        }
      }
      if (!state.negative) settle(state, i, m, visit(state.low_dips, k, looked, d, theta));
      if (!state.negative) walk.wait(state.next, j);
      j = after;
    }
  };
  // The samples' states for the times t ≤ τ shared by every forecast time still to come.
  sign_walk shared(times.size());
  for (std::uint32_t m = 0; m < samples; ++m) shared.follow(m, sign_state{});
  if (slots > 1) {
    // One pass for every forecast time at once: a disc holding the obstacle's reference point under
    // every τ_i at t_k bounds the distance to each of them from below, and the smallest of those
    // distances changes no faster than the centre rate. A sample is not looked at by the walks
    // below before the first time at which it can come within its threshold under some τ_i.
    std::vector<std::size_t> next(samples, 0);
    std::vector<std::size_t> first(samples, std::numeric_limits<std::size_t>::max());
    for (std::size_t k = 0; k < times.size(); ++k) {
      vec2 low = obstacle_pose(0, k).position;
      vec2 high = low;
      for (std::size_t i = 1; i < slots; ++i) {
        const vec2 p = obstacle_pose(i, k).position;
        low = {std::min(low.x, p.x), std::min(low.y, p.y)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y)};
      }
      const vec2 centre = 0.5 * (low + high);
      const double radius = 0.5 * norm(high - low) * (1.0 + 1e-12) + 1e-9;
      if (norm(centre - start) - radius - sweep.reach_radius(k) - reach_ - margin > threshold) continue;
      for (std::size_t m = 0; m < samples; ++m) {
        if (next[m] > k) continue;
        const double own_threshold = sample_threshold(m);
        ++work_.bound_checks;
        const double bound = norm(sweep.at(k, m).position - centre) - radius - reach_ - margin;
        if (bound > own_threshold) {
          next[m] = first_possible(k, bound - own_threshold, centre_rate(m), step);
        } else {
          first[m] = k;
          next[m] = std::numeric_limits<std::size_t>::max();
        }
      }
    }
    for (std::uint32_t m = 0; m < samples; ++m) shared.wait(first[m], m);
  } else {
    for (std::uint32_t m = 0; m < samples; ++m) shared.wait(0, m);
  }
  // Refines the dip still waiting for the time after it (every later time was > θ) and writes what
  // the walk found of sample m under forecast time i: negative, or the exact value of a sample that
  // came within θ; otherwise the +cap placeholder stays.
  const auto conclude = [&](std::size_t i, std::size_t m, sign_state state) {
    if (!state.negative) settle(state, i, m, finish(state.low_dips));
    if (state.negative) {
      sets_[i][m] = -cap;
      ++below_cap_[i];
      ++colliding_[i];
    } else if (state.low) {
      // Every time ≤ θ was looked at and every dip refined: this is the clearance.
      const double c = std::clamp(std::min(state.minimum, state.low_dips.refined), -cap, cap);
      ++work_.exact_values;
      if (c < cap) ++below_cap_[i];
      sets_[i][m] = c;
      exact_[i][m] = 1;
    }
  };
  // Whether sample m touches the obstacle at time index k under forecast time i: the signed
  // distance at a sample time, less the margin, is ≤ 0 (then so is the clearance).
  const auto touches = [&](std::size_t i, std::size_t k, std::size_t m) {
    const obstacle_at o = obstacle_pose(i, k);
    const ego_sweep::placement p = sweep.at(k, m);
    ++work_.bound_checks;
    if (norm(p.position - o.position) - reach_ - margin > 0.0) return false;
    ++work_.distance_evaluations;
    const lower_bound at = distance_or_bound(p, o, 0.0);
    return at.exact && at.value <= 0.0;
  };
  sign_walk walk(times.size());
  std::vector<std::uint8_t> followed(samples);
  std::size_t shared_until = 0;
  for (std::size_t i = 0; i < slots; ++i) {
    for (; shared_until < first_straight_[i]; ++shared_until) advance(shared_until, turning_[shared_until], shared, i);
    // This τ's straight part, for the samples still waiting: a copy of their shared states.
    walk.clear();
    std::fill(followed.begin(), followed.end(), std::uint8_t{0});
    // A sample that touched under an earlier forecast time, at a time after the one it waits for,
    // is tried at that time first: neighbouring forecasts differ little, and one touch at a sample
    // time decides the sign without walking to it.
    for (std::size_t k = shared_until; k < times.size(); ++k) {
      for (std::uint32_t j = shared.head[k]; j != sign_walk::none; j = shared.link[j]) {
        const std::uint32_t m = shared.sample[j];
        const std::uint32_t copy = walk.follow(m, shared.state[j]);
        walk.wait(k, copy);
        followed[m] = 1;
        if (contact[m] != sign_walk::none && contact[m] > k && touches(i, contact[m], m)) walk.state[copy].negative = true;
      }
    }
    for (std::size_t k = shared_until; k < times.size(); ++k) advance(k, obstacle_pose(i, k), walk, i);
    for (std::size_t j = 0; j < walk.sample.size(); ++j) conclude(i, walk.sample[j], walk.state[j]);
    for (std::uint32_t m = 0; m < samples; ++m) {
      if (!followed[m]) conclude(i, m, shared.state[m]);
    }
  }
  if (!near) {
    // Never within the walking cap of any sample: every clearance is exactly +cap.
    inert_ = true;
    for (auto& e : exact_) std::fill(e.begin(), e.end(), std::uint8_t{1});
  }
}

clearance_field::obstacle_at clearance_field::obstacle_pose(std::size_t i, std::size_t k) const {
  if (k < first_straight_[i]) return turning_[k];
  if (independent_) return turning_[k];
  return straight_after_turn(i, sweep_.times()[k]);
}

clearance_field::obstacle_at clearance_field::straight_after_turn(std::size_t i, double t) const {
  const obstacle_at& end = turn_end_[i];
  return {end.position + obstacle_.motion.speed * (t - taus_[i]) * end.direction, end.direction};
}

double clearance_field::clearance_at_time(std::size_t i, std::size_t m, double t) const {
  const ego_sweep::placement e = sweep_.placement_at(m, t);
  obstacle_at o;
  if (t > taus_[i] && !independent_) {
    o = straight_after_turn(i, t);
  } else {
    const pose p = forecast_pose(obstacle_.motion, taus_[i], t);
    o = {p.position, unit_vector(p.heading)};
  }
  return distance(e.position, e.direction, o) - sweep_.window().margin;
}

double clearance_field::distance(vec2 position, vec2 direction, const obstacle_at& o) const {
  if (shapes_ == shape_pair::rectangles) {
    return signed_distance(placed_rectangle{position, direction, ego_half_.x, ego_half_.y},
                           placed_rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y});
  }
  if (shapes_ == shape_pair::rectangle_disc) {
    return signed_distance(placed_rectangle{position, direction, ego_half_.x, ego_half_.y}, o.position,
                           obstacle_radius_);
  }
  return signed_distance(place(sweep_.ego().shape, position, direction), place(obstacle_.shape, o.position, o.direction));
}

clearance_field::lower_bound clearance_field::distance_or_bound(const ego_sweep::placement& p, const obstacle_at& o,
                                                                 double enough) const {
  const double margin = sweep_.window().margin;
  if (shapes_ != shape_pair::rectangles) return {distance(p.position, p.direction, o) - margin, true};
  // `distance`'s arithmetic, with the face separation looked at before the corners.
  const placed_rectangle ego{p.position, p.direction, ego_half_.x, ego_half_.y};
  const placed_rectangle obstacle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
  const double separation = face_separation(ego, obstacle);
  if (separation <= 0.0) return {separation - margin, true};
  if (const double bound = separation - margin - rounding_slack; bound >= enough) return {bound, false};
  return {corner_distance(ego, obstacle) - margin, true};
}

double clearance_field::refined_at(std::size_t i, std::size_t m, std::size_t k, double at_sample) {
  const auto at = [&](double t) { return clearance_at_time(i, m, t); };
  // On the shared times (t ≤ τ) the search sees the same function for every τ: search once.
  const bool shared = k + 1 < first_straight_[i];
  if (shared) {
    for (const auto& [argmin, value] : refined_[m]) {
      if (argmin == k) return value;
    }
  }
  ++work_.refinements;
  const double value = refined_minimum(sweep_.times(), k, at, at_sample);
  if (shared) refined_[m].emplace_back(k, value);
  return value;
}

clearance_field::dip clearance_field::finish(dips& d) {
  dip pending;
  if (d.candidate != dips::no_index) pending = {d.candidate, d.candidate_value};
  d.candidate = dips::no_index;
  return pending;
}

double clearance_field::exact(std::size_t forecast, std::size_t m) {
  const std::size_t i = slot(forecast);
  if (exact_[i][m]) return sets_[i][m];
  const std::size_t count = sweep_.times().size();
  const double step = sweep_.window().time_step;
  const double margin = sweep_.window().margin;
  const double centre = centre_rate(m);
  const double rate = distance_rate(m);
  const double theta = sample_threshold(m);
  // Below this a time can matter: under the running minimum, or ≤ θ while nothing has touched
  // (then every dip ≤ θ is refined).
  const auto level = [&](const running_minimum& r) {
    const double known = std::min(r.value, walk_cap_);
    return r.value > 0.0 ? std::max(known, theta) : known;
  };
  const auto settle = [&](dips& low, const dip& d) {
    if (d.at != dips::no_index) low.refined = std::min(low.refined, refined_at(i, m, d.at, d.value));
  };
  // Looks at time index k and returns the next one that can matter.
  const auto look = [&](std::size_t k, const obstacle_at& o, running_minimum& r, dips& low) {
    const double known = std::min(r.value, walk_cap_);
    if (known <= -walk_cap_) return std::numeric_limits<std::size_t>::max();
    const ego_sweep::placement p = sweep_.at(k, m);
    ++work_.bound_checks;
    const double bound = norm(p.position - o.position) - reach_ - margin;
    if (bound >= known && (r.value <= 0.0 || bound > theta)) {
      if (r.value > 0.0) settle(low, visit(low, k, false, 0.0, theta));
      return first_possible(k, bound - level(r), centre, step);
    }
    // A lower bound of at least this leaves the running minimum and the dips as they are.
    const double enough = r.value > 0.0 ? std::max(known, std::nextafter(theta, walk_cap_)) : known;
    const lower_bound at = distance_or_bound(p, o, enough);
    if (!at.exact) {
      if (r.value > 0.0) settle(low, visit(low, k, false, 0.0, theta));
      return first_possible(k, at.value - level(r), rate, step);
    }
    const double d = at.value;
    r.update(d, k);
    ++work_.distance_evaluations;
    if (r.value > 0.0) settle(low, visit(low, k, true, d, theta));
    return first_possible(k, d - level(r), rate, step);
  };
  // The shared times first (kept for larger τ), then this τ's straight part.
  prefix_walk& prefix = prefix_[m];
  const std::size_t shared = first_straight_[i];
  if (prefix.until > shared) prefix = prefix_walk{};
  for (; prefix.next < shared; prefix.next = look(prefix.next, turning_[prefix.next], prefix.minimum, prefix.low)) {
  }
  prefix.until = shared;
  running_minimum r = prefix.minimum;
  dips low = prefix.low;
  for (std::size_t k = prefix.next; k < count;) k = look(k, obstacle_pose(i, k), r, low);
  double c = r.value;
  if (c > 0.0 && c <= theta) {
    settle(low, finish(low));
    c = std::min(c, low.refined);
  } else if (c > -walk_cap_ && c < walk_cap_) {
    c = std::min(c, refined_at(i, m, r.argmin, r.at_argmin));
  }
  c = std::clamp(c, -cap_, cap_);
  ++work_.exact_values;
  if (sets_[i][m] >= cap_ && c < cap_) ++below_cap_[i];
  sets_[i][m] = c;
  exact_[i][m] = 1;
  return c;
}

double clearance_field::exact_below(std::size_t forecast, std::size_t m, double ceiling) {
  const std::size_t i = slot(forecast);
  if (exact_[i][m] || ceiling >= cap_) return exact(forecast, m);
  const std::size_t count = sweep_.times().size();
  const double step = sweep_.window().time_step;
  const double margin = sweep_.window().margin;
  const double centre = centre_rate(m);
  const double rate = distance_rate(m);
  // Sampled values at or above this keep every value in between, and so the refined minimum,
  // at or above the ceiling: between samples the signed distance falls by at most L·step/2.
  const double limit = ceiling + refinement_threshold(rate, step);
  if (limit >= walk_cap_) return exact(forecast, m);  // the exact walk prunes as much
  std::vector<double>& floor = floor_[i];
  if (!floor.empty() && floor[m] >= ceiling) return floor[m];
  std::size_t k = 0;
  // A walk over the shared times t ≤ τ_i (kept from an earlier exact value) bounds them all.
  const prefix_walk& prefix = prefix_[m];
  const std::size_t shared = first_straight_[i];
  if (shared > 0 && prefix.until >= shared) {
    if (std::min(prefix.minimum.value, walk_cap_) < limit) return exact(forecast, m);
    k = shared;
  }
  while (k < count) {
    const obstacle_at o = obstacle_pose(i, k);
    const ego_sweep::placement p = sweep_.at(k, m);
    ++work_.bound_checks;
    const double bound = norm(p.position - o.position) - reach_ - margin;
    if (bound >= limit) {
      k = first_possible(k, bound - limit, centre, step);
      continue;
    }
    const lower_bound at = distance_or_bound(p, o, limit);
    if (at.exact) {
      ++work_.distance_evaluations;
      if (at.value < limit) return exact(forecast, m);
    }
    k = first_possible(k, at.value - limit, rate, step);
  }
  if (floor.empty()) floor.assign(sweep_.sample_count(), -cap_);
  floor[m] = ceiling;
  return ceiling;
}

void clearance_field::make_all_exact() {
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    for (std::size_t m = 0; m < sets_[i].size(); ++m) exact(i, m);
  }
}

std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap) {
  clearance_field field(sweep, obstacle, forecast_times, cap);
  field.make_all_exact();
  std::vector<clearance_set> result;
  for (std::size_t i = 0; i < field.forecast_count(); ++i) result.push_back(field.set(i));
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
    std::vector<double> d(times.size());
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const maneuver& u = samples.maneuvers[m];
      const auto at = [&](double t) { return clearance_at(ego, u, obstacle, tau, t, window); };
      const double theta = refinement_threshold(
          largest_point_speed(ego, u, window.horizon) + largest_point_speed(obstacle), window.time_step);
      running_minimum r;
      for (std::size_t k = 0; k < times.size(); ++k) {
        d[k] = at(times[k]);
        r.update(d[k], k);
      }
      double c = r.value;
      if (c > 0.0 && c <= theta) {
        // Passes within θ without touching at a sample time: refine every dip ≤ θ.
        for (std::size_t j = 0; j < times.size(); ++j) {
          const bool dip = d[j] <= theta && (j == 0 || d[j] <= d[j - 1]) && (j + 1 == times.size() || d[j] <= d[j + 1]);
          if (dip) c = std::min(c, refined_minimum(times, j, at, d[j]));
        }
      } else {
        c = std::min(c, refined_minimum(times, r.argmin, at, r.at_argmin));
      }
      clearance[m] = c;
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
