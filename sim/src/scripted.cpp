#include "mm/sim/scripted.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mm::sim {
namespace {

/// A piece of the profile on which the speed is linear: from clock `begin` for `duration`
/// (∞ for the last), starting at `speed` with slope `acceleration`.
struct piece {
  double begin;
  double duration;
  double speed;
  double acceleration;
};

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
    distance += p.speed * x + 0.5 * p.acceleration * x * x;
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
    const double covered = p.speed * p.duration + 0.5 * p.acceleration * p.duration * p.duration;
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

scripted_sample scripted_state(const scripted_motion& motion, double time) {
  scripted_sample sample;
  sample.arc_length = motion.start_arc_length;
  if (time < motion.start_time) return sample;
  double clock = time - motion.start_time;
  if (motion.stop) {
    const std::optional<double> reached =
        profile_time_to_cover(motion.speed, motion.stop->arc_length - motion.start_arc_length);
    if (reached && clock >= *reached) {
      if (!motion.stop->duration || clock < *reached + *motion.stop->duration) {
        sample.phase = motion_phase::stopped;
        sample.arc_length = motion.stop->arc_length;
        return sample;
      }
      clock -= *motion.stop->duration;
    }
  }
  sample.arc_length = motion.start_arc_length + profile_distance(motion.speed, clock);
  sample.speed = profile_speed(motion.speed, clock);
  sample.acceleration = profile_acceleration(motion.speed, clock);
  sample.phase = sample.arc_length >= motion.path.length() ? motion_phase::finished : motion_phase::moving;
  return sample;
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
