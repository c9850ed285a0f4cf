#pragma once

#include <limits>
#include <optional>

#include "mm/maneuver.hpp"
#include "mm/sim/path.hpp"
#include "mm/sim/scripted.hpp"

namespace mm::sim {

/// Keeping a distance to the road user ahead on the path: the interaction term of the Intelligent
/// Driver Model (Treiber, Hennecke and Helbing 2000). An addition to spec §8, whose u_nom keeps only
/// to the path and the desired speed, so that a planning vehicle closes up to the planner's safety
/// margin behind a slower one (docs/simulator.md §5).
struct car_following_config {
  double time_gap = 1.0;      ///< T [s] ≥ 0: the gap kept grows by v·T at speed v
  double jam_distance = 2.0;  ///< s0 [m] ≥ 0: the gap kept at a standstill, bumper to bumper
  /// [m] > 0: a road user whose reference point is this close beside the path, ahead on it, is
  /// followed (half a lane).
  double corridor_half_width = 1.75;
  /// [rad] in [0, π]: and whose heading differs from the path's there by at most this. Crossing and
  /// oncoming traffic is the planner's to avoid, not the driver's to follow (a vehicle that follows
  /// whatever enters its corridor stops for every merging one, and a busy roundabout jams).
  double max_heading_difference = 0.785398163397448;  // 45°

  friend bool operator==(const car_following_config&, const car_following_config&) = default;
};

/// The road user a follower keeps its distance to.
struct leader {
  double gap = 0.0;    ///< s [m]: from the follower's front to the leader's rear, along the path
  double speed = 0.0;  ///< the leader's speed along the path [m/s] (negative when it comes toward)
};

/// The largest acceleration car following allows [m/s²]: a·(1 − (s*/s)²) with the desired gap
/// s* = s0 + max(0, v·T + v·Δv / (2√(a·b))), Δv = v − v_leader, a the vehicle's largest
/// acceleration and b its comfortable deceleration; −∞ when the gap s ≤ 0. It is 0 at s = s*,
/// positive beyond and negative within, so a follower that takes min(its own, this) settles at s*
/// behind a leader of constant speed.
double car_following_acceleration(double speed, const leader& ahead, const car_following_config& config,
                                  double max_acceleration, double comfortable_deceleration);

/// Car following for a scripted vehicle, an addition to spec §8 (docs/simulator.md §4). The vehicle
/// keeps to its script while car following lets it; once `car_following_acceleration` behind the
/// road user ahead on its path allows less than the script's acceleration, it lags behind the
/// script, with `lagging_acceleration`, until it has caught up with it again (or reached the
/// path's end). It is never ahead of its script: it can only be later along the same path.
struct scripted_car_following {
  car_following_config following;
  double max_acceleration = 3.0;          ///< a [m/s²] > 0, of the car-following term and of catching up (spec §3's a_max)
  double comfortable_deceleration = 2.0;  ///< b [m/s²] > 0, of the car-following term
  double max_deceleration = 7.0;          ///< d_max [m/s²] > 0: its hardest braking (spec §3's default)
  double speed_gain = 1.0;                ///< k_v [1/s] > 0: how fast it takes up its script again
  /// true: it follows whatever road user is ahead; false: only those that do not keep to a script
  /// (planning vehicles, and scripted vehicles that lag behind theirs), for scripts whose
  /// interactions with each other are already in them, as a recording's are (a reactive replay).
  bool follows_scripted = true;

  friend bool operator==(const scripted_car_following&, const scripted_car_following&) = default;
};

/// The acceleration of a scripted vehicle at arc length s [m] and speed v [m/s] that lags behind
/// its script `script` (its state at the same time, with its acceleration over the coming step)
/// [m/s²]: it closes on the script,
/// a = a_script + k_v·(v_script − v) + k_v²·(s_script − s) (a spring of natural frequency k_v,
/// damped at half the critical rate, so that it reaches the script rather than creeping up on it),
/// at most `cap` (car following's; +∞ without a leader), and within [−d_max, a_max].
double lagging_acceleration(double arc_length, double speed, const scripted_sample& script, double cap,
                            const scripted_car_following& config);

/// Parameters of the path follower that produces the nominal maneuver u_nom (spec §8).
struct follower_config {
  double lookahead_time = 0.8;            ///< k_L [s]: lookahead L_d = max(L_min, k_L·v); > 0
  double min_lookahead = 5.0;             ///< L_min [m] > 0
  double speed_gain = 1.0;                ///< k_v [1/s] > 0 of the speed P-controller
  double comfortable_deceleration = 2.0;  ///< b [m/s²] > 0: how hard it brakes ahead of a curve
  /// a_lat [m/s²] of the curve speed limit v²|κ| ≤ a_lat; none: the vehicle's
  /// `ego_limits::max_lateral_acceleration` (spec §8).
  std::optional<double> curve_lateral_acceleration;
  /// Keeping a distance to the road user ahead (`car_following_acceleration`); none: off, as in
  /// spec §8.
  std::optional<car_following_config> car_following;

  friend bool operator==(const follower_config&, const follower_config&) = default;
};

/// Lookahead distance L_d = max(L_min, k_L·v) [m].
double lookahead_distance(double speed, const follower_config& config);

/// Pure-pursuit curvature toward `goal` [1/m]: κ = 2·y / (x² + y²) where (x, y) is the goal in the
/// vehicle frame (x forward, y left): the circle through the vehicle, tangent to its heading, that
/// passes through the goal. 0 when the goal is at the vehicle.
double pure_pursuit_curvature(const mm::pose& vehicle, vec2 goal);

/// The speed limit imposed by the curves ahead.
struct curve_speed_limit {
  /// v_lim = min over curves of √(v_c² + 2·b·d) [m/s]: the highest speed from which braking at b
  /// reaches each curve's speed v_c = √(a_lat / |κ|) by its start, d ≥ 0 ahead. ∞ without curves.
  double speed = std::numeric_limits<double>::infinity();
  double curve_speed = std::numeric_limits<double>::infinity();  ///< v_c of the binding curve [m/s]
  double distance = 0.0;  ///< d to the binding curve's start [m]; 0 when already on it
};

/// Curve speed limit at arc length `arc_length` [m] from the path's curvature over
/// [arc_length, arc_length + preview] [m], with lateral acceleration `lateral_acceleration` [m/s²]
/// and braking deceleration `deceleration` [m/s²]. Curves farther than v²/(2b) cannot bind at
/// speed v, so a preview of max(v, v_des)²/(2b) plus the lookahead suffices.
curve_speed_limit curve_speed_limit_ahead(const path& reference, double arc_length, double preview,
                                          double lateral_acceleration, double deceleration);

/// What the follower wants to do at one instant.
struct follower_command {
  maneuver nominal;            ///< u_nom = (a_nom, κ_nom), within the limits at the current speed
  double lookahead = 0.0;      ///< L_d [m]
  vec2 goal;                   ///< the pursued point, path point at s + L_d [m]
  double target_speed = 0.0;   ///< v_t = min(v_des, curve limit) [m/s]
};

/// The nominal maneuver of spec §8 for a vehicle at `vehicle` with speed v [m/s] whose
/// projection on `reference` is at `arc_length` [m]:
/// - κ_nom: pure pursuit of the path point at s + L_d (on the straight extension past the end);
/// - a_nom = k_v·(v_t − v) + a_ff, v_t = min(v_des, v_lim); a_ff = −b while braking toward a curve
///   ahead (d > 0, v > v_c), which is the deceleration that keeps v on the braking profile
///   √(v_c² + 2·b·d); 0 otherwise;
/// both clamped to the limits (a ∈ [−d_max, a_max], |κ| ≤ κ_max(v)).
follower_command follow_path(const path& reference, double arc_length, const mm::pose& vehicle, double speed,
                             double desired_speed, const follower_config& config, const ego_limits& limits);

}  // namespace mm::sim
