#pragma once

#include <limits>
#include <optional>

#include "mm/maneuver.hpp"
#include "mm/sim/path.hpp"

namespace mm::sim {

/// Parameters of the path follower that produces the nominal maneuver u_nom (spec §8).
struct follower_config {
  double lookahead_time = 0.8;            ///< k_L [s]: lookahead L_d = max(L_min, k_L·v); > 0
  double min_lookahead = 5.0;             ///< L_min [m] > 0
  double speed_gain = 1.0;                ///< k_v [1/s] > 0 of the speed P-controller
  double comfortable_deceleration = 2.0;  ///< b [m/s²] > 0: how hard it brakes ahead of a curve
  /// a_lat [m/s²] of the curve speed limit v²|κ| ≤ a_lat; none: the vehicle's
  /// `ego_limits::max_lateral_acceleration` (spec §8).
  std::optional<double> curve_lateral_acceleration;
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
