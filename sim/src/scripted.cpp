#include "mm/sim/scripted.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mm::sim {
namespace {

using piece = tabulated_profile::piece;

/// The pieces of the profile in order: constant before the first knot, linear between knots,
/// constant after the last.
std::vector<piece> pieces(const speed_profile& profile) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<piece> result;
  const auto& k = profile.knots;
  if (k.empty()) return {{0.0, inf, 0.0, 0.0}};
  if (k.front().time > 0.0) result.push_back({0.0, k.front().time, k.front().speed, 0.0});
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const double dt = k[i + 1].time - k[i].time;
    result.push_back({k[i].time, dt, k[i].speed, (k[i + 1].speed - k[i].speed) / dt});
  }
  result.push_back({std::max(k.back().time, 0.0), inf, k.back().speed, 0.0});
  return result;
}

/// The distance covered in the first `x` seconds of piece `p` [m]: v·x + a·x²/2. Every distance of
/// the profile is a sum of these, so the reference and the table add the same terms.
double covered_within(const piece& p, double x) { return p.speed * x + 0.5 * p.acceleration * x * x; }

/// The piece that contains clock τ (the later one on a knot).
piece piece_at(const std::vector<piece>& all, double clock) {
  for (const piece& p : all) {
    if (clock < p.begin + p.duration) return p;
  }
  return all.back();
}

}  // namespace

double profile_speed(const speed_profile& profile, double clock) {
  const piece p = piece_at(pieces(profile), std::max(clock, 0.0));
  return std::max(0.0, p.speed + p.acceleration * (std::max(clock, 0.0) - p.begin));
}

double profile_acceleration(const speed_profile& profile, double clock) {
  return piece_at(pieces(profile), std::max(clock, 0.0)).acceleration;
}

double profile_distance(const speed_profile& profile, double clock) {
  double distance = 0.0;
  for (const piece& p : pieces(profile)) {
    if (clock <= p.begin) break;
    const double x = std::min(clock - p.begin, p.duration);
    distance += covered_within(p, x);
  }
  return distance;
}

std::optional<double> profile_time_to_cover(const speed_profile& profile, double distance) {
  if (distance <= 0.0) return 0.0;
  double remaining = distance;
  for (const piece& p : pieces(profile)) {
    if (std::isinf(p.duration)) {
      if (p.speed <= 0.0) return std::nullopt;
      return p.begin + remaining / p.speed;
    }
    const double covered = covered_within(p, p.duration);
    if (remaining <= covered) {
      // v_a·x + a·x²/2 = remaining, the root in [0, duration], in the form that is stable for a → 0.
      const double root = std::sqrt(std::max(0.0, p.speed * p.speed + 2.0 * p.acceleration * remaining));
      const double x = p.speed + root > 0.0 ? 2.0 * remaining / (p.speed + root) : p.duration;
      return p.begin + std::min(x, p.duration);
    }
    remaining -= covered;
  }
  return std::nullopt;
}

std::string_view to_string(before_start_behaviour behaviour) {
  switch (behaviour) {
    case before_start_behaviour::absent: return "absent";
    case before_start_behaviour::wait: return "wait";
  }
  return "unknown";
}

namespace {

/// The state of `motion` at `time`, its profile evaluated by `profile` (speed, acceleration and
/// distance at a clock) and `reached()` the clock at which it reaches its stop.
template <class Profile, class Reached>
scripted_sample state_of(const scripted_motion& motion, double time, const Profile& profile, const Reached& reached) {
  scripted_sample sample;
  sample.arc_length = motion.start_arc_length;
  if (time < motion.start_time) return sample;
  double clock = time - motion.start_time;
  if (motion.stop) {
    const std::optional<double> at = reached();
    if (at && clock >= *at) {
      if (!motion.stop->duration || clock < *at + *motion.stop->duration) {
        sample.phase = motion_phase::stopped;
        sample.arc_length = motion.stop->arc_length;
        return sample;
      }
      clock -= *motion.stop->duration;
    }
  }
  sample.arc_length = motion.start_arc_length + profile.distance(clock);
  sample.speed = profile.speed(clock);
  sample.acceleration = profile.acceleration(clock);
  sample.phase = sample.arc_length >= motion.path.length() ? motion_phase::finished : motion_phase::moving;
  return sample;
}

/// The reference's evaluation: the free functions, every call from the knots.
struct walked_profile {
  const speed_profile& profile;
  double speed(double clock) const { return profile_speed(profile, clock); }
  double acceleration(double clock) const { return profile_acceleration(profile, clock); }
  double distance(double clock) const { return profile_distance(profile, clock); }
};

std::optional<double> stop_reached(const scripted_motion& motion) {
  return profile_time_to_cover(motion.speed, motion.stop->arc_length - motion.start_arc_length);
}

}  // namespace

scripted_sample scripted_state(const scripted_motion& motion, double time) {
  return state_of(motion, time, walked_profile{motion.speed}, [&] { return stop_reached(motion); });
}

tabulated_profile::tabulated_profile(const speed_profile& profile) : pieces_(pieces(profile)) {
  double end = -std::numeric_limits<double>::infinity();
  double covered = 0.0;
  for (const piece& p : pieces_) {
    end = std::max(end, p.begin + p.duration);
    end_so_far_.push_back(end);
    covered_.push_back(covered);
    if (std::isfinite(p.duration)) covered += covered_within(p, p.duration);
  }
}

/// `piece_at`'s piece: the first with clock < begin + duration, which is the first whose running
/// maximum of those ends exceeds the clock; the last when there is none.
std::size_t tabulated_profile::index_at(double clock) const {
  const auto found = std::upper_bound(end_so_far_.begin(), end_so_far_.end(), clock);
  return found == end_so_far_.end() ? pieces_.size() - 1 : static_cast<std::size_t>(found - end_so_far_.begin());
}

double tabulated_profile::speed(double clock) const {
  const piece& p = pieces_[index_at(std::max(clock, 0.0))];
  return std::max(0.0, p.speed + p.acceleration * (std::max(clock, 0.0) - p.begin));
}

double tabulated_profile::acceleration(double clock) const {
  return pieces_[index_at(std::max(clock, 0.0))].acceleration;
}

/// `profile_distance` adds, in order, every piece that begins before the clock: the pieces before
/// the last of them whole (a later one begins before the clock, so clock − begin ≥ duration), the
/// last up to the clock.
double tabulated_profile::distance(double clock) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), clock,
                                      [](double c, const piece& p) { return c <= p.begin; });
  if (after == pieces_.begin()) return 0.0;
  const std::size_t last = static_cast<std::size_t>(after - pieces_.begin()) - 1;
  const piece& p = pieces_[last];
  const double x = std::min(clock - p.begin, p.duration);
  return covered_[last] + covered_within(p, x);
}

prepared_script::prepared_script(const scripted_motion& motion)
    : motion_(&motion), speed_(motion.speed), stop_reached_(motion.stop ? stop_reached(motion) : std::nullopt) {}

scripted_sample prepared_script::state(double time) const {
  return state_of(*motion_, time, speed_, [this] { return stop_reached_; });
}

std::optional<double> time_to_reach(const scripted_motion& motion, double arc_length) {
  if (arc_length < motion.start_arc_length) return std::nullopt;
  const std::optional<double> clock = profile_time_to_cover(motion.speed, arc_length - motion.start_arc_length);
  if (!clock) return std::nullopt;
  double paused = 0.0;
  if (motion.stop && arc_length > motion.stop->arc_length) {
    if (!motion.stop->duration) return std::nullopt;
    paused = *motion.stop->duration;
  }
  return motion.start_time + *clock + paused;
}

}  // namespace mm::sim
