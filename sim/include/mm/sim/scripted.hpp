#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "mm/sim/path.hpp"

namespace mm::sim {

/// One knot of a speed profile.
struct speed_knot {
  double time = 0.0;   ///< on the agent's own clock: seconds since its start, stops not counted [s], ≥ 0
  double speed = 0.0;  ///< [m/s], ≥ 0

  friend bool operator==(const speed_knot&, const speed_knot&) = default;
};

/// Speed as a piecewise-linear function of the agent's own clock τ: linear between knots, the
/// first knot's speed before the first knot, the last knot's speed after the last one. Knot
/// times strictly increase. Distances are integrated exactly (piecewise quadratic).
struct speed_profile {
  std::vector<speed_knot> knots;

  /// A constant speed v [m/s].
  static speed_profile constant(double speed) { return {{{0.0, speed}}}; }

  friend bool operator==(const speed_profile&, const speed_profile&) = default;
};

/// v(τ) [m/s]; τ < 0 counts as 0.
double profile_speed(const speed_profile& profile, double clock);

/// dv/dτ [m/s²] (the slope of the piece that starts at τ).
double profile_acceleration(const speed_profile& profile, double clock);

/// D(τ) = ∫₀^τ v(τ') dτ' [m]; 0 for τ ≤ 0.
double profile_distance(const speed_profile& profile, double clock);

/// The smallest τ ≥ 0 with D(τ) = `distance` [m]; none if the profile never covers it (it ends
/// at rest first).
std::optional<double> profile_time_to_cover(const speed_profile& profile, double distance);

/// Where a not-yet-started agent is.
enum class before_start_behaviour : std::uint8_t {
  absent,  ///< not in the world: neither observed nor collidable until its start time (default)
  wait,    ///< standing at its start pose with speed 0: observed and collidable
};

std::string_view to_string(before_start_behaviour behaviour);

/// A stop on the path, e.g. a pedestrian waiting at the kerb.
struct stop_rule {
  double arc_length = 0.0;         ///< s_stop [m] on the path, ≥ the start arc length
  std::optional<double> duration;  ///< how long the agent stands [s], > 0; none: for ever

  friend bool operator==(const stop_rule&, const stop_rule&) = default;
};

/// Motion of a scripted agent (scripted vehicle or pedestrian): it follows `path` exactly (no
/// lateral deviation, heading = path tangent), ignoring every other agent.
///
/// Before `start_time` it is absent or waits (see `before_start`); from then on its own clock
/// τ = t − start_time runs and s(τ) = s0 + D(τ). On reaching `stop` it halts at once (speed 0)
/// and its clock pauses for the stop's duration; then it resumes the profile where it left off
/// (so the speed jumps back to the profile's value). On reaching the end of the path it leaves
/// the scene.
struct scripted_motion {
  mm::sim::path path;
  double start_time = 0.0;        ///< [s], ≥ 0
  double start_arc_length = 0.0;  ///< s0 [m], 0 ≤ s0 < path length
  before_start_behaviour before_start = before_start_behaviour::absent;
  speed_profile speed = speed_profile::constant(0.0);
  std::optional<stop_rule> stop;

  friend bool operator==(const scripted_motion&, const scripted_motion&) = default;
};

/// Where a scripted agent is in its life.
enum class motion_phase : std::uint8_t { not_started, moving, stopped, finished };

/// The scripted state at one time.
struct scripted_sample {
  motion_phase phase = motion_phase::not_started;
  double arc_length = 0.0;    ///< s [m] (s0 before the start; ≥ path length once finished)
  double speed = 0.0;         ///< [m/s]; 0 before the start and while stopped
  double acceleration = 0.0;  ///< [m/s²]
};

/// The exact (closed-form) state of `motion` at absolute time `time` [s].
scripted_sample scripted_state(const scripted_motion& motion, double time);

/// A speed profile prepared for evaluation many times: its pieces, their ends and the distance
/// covered before each are computed once, so that speed, acceleration and distance at a clock take
/// O(log K) for K knots and allocate nothing, where `profile_speed`, `profile_acceleration` and
/// `profile_distance` (the reference) build the pieces and walk them, O(K). The values are theirs,
/// bit for bit: the same pieces, the same sums in the same order (tests/sim/scripted_test.cpp). A
/// replayed recording has two knots per recorded step, so the reference makes a replay's cost grow
/// with the square of its length.
class tabulated_profile {
 public:
  explicit tabulated_profile(const speed_profile& profile);

  double speed(double clock) const;         ///< = profile_speed(profile, clock) [m/s]
  double acceleration(double clock) const;  ///< = profile_acceleration(profile, clock) [m/s²]
  double distance(double clock) const;      ///< = profile_distance(profile, clock) [m]

  /// A piece of the profile on which the speed is linear: from clock `begin` for `duration` (∞
  /// for the last), starting at `speed` with slope `acceleration`.
  struct piece {
    double begin;
    double duration;
    double speed;
    double acceleration;
  };

 private:
  std::size_t index_at(double clock) const;

  std::vector<piece> pieces_;
  std::vector<double> end_so_far_;   ///< max over pieces 0..i of begin + duration: sorted
  std::vector<double> covered_;      ///< distance covered by the whole pieces 0..i−1 [m]
};

/// A scripted motion prepared for evaluation at every step of a run: `state(time)` gives
/// `scripted_state(motion, time)`, bit for bit, in O(log K) for K knots of its speed profile (its
/// profile tabulated, the time it reaches its stop computed once). Keeps a reference to `motion`.
class prepared_script {
 public:
  explicit prepared_script(const scripted_motion& motion);

  scripted_sample state(double time) const;
  const scripted_motion& motion() const { return *motion_; }

 private:
  const scripted_motion* motion_;
  tabulated_profile speed_;
  std::optional<double> stop_reached_;  ///< the clock at which it reaches its stop
};

/// The absolute time [s] at which `motion` first reaches arc length `arc_length` [m]: use it to
/// time a conflict. None if it never does (behind its start, beyond a permanent stop, or the
/// profile comes to rest before).
std::optional<double> time_to_reach(const scripted_motion& motion, double arc_length);

}  // namespace mm::sim
