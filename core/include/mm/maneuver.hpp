#pragma once

#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm {

/// Limits of the ego vehicle A (spec §3). All values positive.
struct ego_limits {
  double max_acceleration = 3.0;          ///< a_max [m/s²]
  double max_deceleration = 7.0;          ///< d_max [m/s²], a positive number
  double max_lateral_acceleration = 5.0;  ///< a_lat_max [m/s²]
  double min_turning_radius = 5.5;        ///< R_min [m], geometric
  double speed_cap = 30.0;                ///< v_cap [m/s], hard cap (not the desired speed)
  bool steering = true;                   ///< false: κ_max = 0, the one-dimensional case of spec §10
  friend constexpr bool operator==(const ego_limits&, const ego_limits&) = default;
};

/// The ego vehicle as the planner sees it.
struct ego_state {
  mm::pose pose;                                  ///< reference point and heading
  double speed = 0.0;                         ///< v0 [m/s], 0 ≤ v0 ≤ v_cap
  footprint shape = rectangle{};              ///< spec §2 default 4.5 m × 1.8 m
  ego_limits limits;
};

/// A maneuver u = (a, κ) [Δa, κ]: constant longitudinal acceleration [m/s²] and constant path
/// curvature [1/m], positive to the left (spec §3).
struct maneuver {
  double acceleration = 0.0;
  double curvature = 0.0;

  friend constexpr bool operator==(const maneuver&, const maneuver&) = default;
};

/// κ_max(v) = min(1/R_min, a_lat_max / v²) [1/m]; 1/R_min near standstill; 0 without steering (§3).
double max_curvature(double speed, const ego_limits& limits);

/// v(t) = clamp(v0 + a·t, 0, v_cap) [m/s] (§3).
double speed_after(double initial_speed, double acceleration, double t, double speed_cap);

/// s(t) = ∫₀ᵗ clamp(v0 + a·τ, 0, v_cap) dτ [m]: travelled arc length, stopping at zero speed (§3).
/// Where the speed stays clearly inside [0, v_cap] up to t, the one trapezoid without the divisions
/// that find where it would leave: equal bit for bit to `travelled_distance_reference`.
double travelled_distance(double initial_speed, double acceleration, double t, double speed_cap);

/// The reference for `travelled_distance`: the trapezoid rule on each piece between the times at
/// which the speed reaches 0 and v_cap (exact, the speed being linear on each).
double travelled_distance_reference(double initial_speed, double acceleration, double t, double speed_cap);

/// End point of a circular arc of curvature κ [1/m] and arc length s [m] in the frame of its start
/// (x forward): (sin(κs)/κ, (1 − cos κs)/κ), the straight segment (s, 0) when κ = 0 (§3).
vec2 arc_point(double curvature, double arc_length);

/// A reference point [m] and the heading as a unit vector (cos θ, sin θ): what a footprint is placed by.
struct placement {
  vec2 position;
  vec2 direction;
};

/// `maneuver_pose` in the frame of the start (x forward, heading 0 at t = 0), the heading as a unit
/// vector: position [m] and direction relative to the start. One sine and cosine of half the turn
/// κs give both: sin κs = 2 sin(κs/2) cos(κs/2), 1 − cos κs = 2 sin²(κs/2).
placement maneuver_local_placement(double initial_speed, const maneuver& u, double t, double horizon, double speed_cap);

/// The arc part of `maneuver_local_placement`: the placement after arc length s [m] on an arc of
/// curvature κ [1/m], in the frame of its start; `maneuver_local_placement` at t ≤ horizon is
/// `arc_placement(travelled_distance(v0, a, t, v_cap), κ)`, bit for bit.
placement arc_placement(double arc_length, double curvature);

/// `maneuver_local_placement` in the world: rotated by `start_direction` = (cos, sin) of
/// `start.heading` and moved to `start.position`. What the collision tests place the ego by.
placement maneuver_placement(const pose& start, vec2 start_direction, double initial_speed, const maneuver& u,
                             double t, double horizon, double speed_cap);

/// `maneuver_pose` in the frame of the start (x forward, heading 0 at t = 0): position [m] and
/// heading [rad] relative to the start.
pose maneuver_local_pose(double initial_speed, const maneuver& u, double t, double horizon, double speed_cap);

/// Pose at time t [s] of the ego executing `u` from `start` at speed v0 (spec §5): the arc of `u`
/// on [0, horizon], then straight ahead at the speed and heading reached at `horizon` [T_h].
pose maneuver_pose(const pose& start, double initial_speed, const maneuver& u, double t,
                   double horizon, double speed_cap);

/// `u` clamped into the limits at speed v0: a ∈ [−d_max, a_max], |κ| ≤ κ_max(v0).
maneuver clamp_to_limits(const maneuver& u, double initial_speed, const ego_limits& limits);

}  // namespace mm
