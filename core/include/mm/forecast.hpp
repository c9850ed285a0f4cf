#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm {

/// What an obstacle is. All kinds are tracked and forecast the same way (spec §4); a static
/// obstacle is taken to stand still and may be observed only once.
enum class obstacle_kind : std::uint8_t { vehicle, pedestrian, static_obstacle };

std::string_view to_string(obstacle_kind kind);

/// One observation of an obstacle: time [s], pose, speed [m/s] (possibly noisy).
struct observation {
  double time = 0.0;
  mm::pose pose;
  double speed = 0.0;
};

/// The planner's estimate of an obstacle's motion at the planning time (spec §4).
struct motion_estimate {
  mm::pose pose;               ///< at the planning time
  double speed = 0.0;      ///< v_j [m/s], ≥ 0
  double yaw_rate = 0.0;   ///< ω_j [rad/s], counter-clockwise positive
};

/// An observed obstacle: its footprint and its observation history, oldest first, strictly
/// increasing times. Vehicles and pedestrians need at least two observations, or one and `motion`.
struct obstacle_track {
  std::uint32_t id = 0;
  obstacle_kind kind = obstacle_kind::vehicle;
  footprint shape = rectangle{};
  std::vector<observation> history;
  /// The motion at the planning time when the caller estimated it already (a tracker of its own,
  /// or a simulator that estimates each road user once for all its observers): the planner then
  /// uses it instead of `estimate_motion(track, config.history_window, time)` (spec §4). Empty:
  /// the planner estimates it from the history.
  std::optional<motion_estimate> motion;
};

/// Least-squares estimate of speed v_j and yaw rate ω_j from the observations in the window
/// [t_last − history_window, t_last] (at least the last two) (spec §4):
/// - ω_j is the slope of the line fitted to the unwrapped headings, clamped to
///   ±`largest_input_yaw_rate`; the heading is that line's value at t_last;
/// - v_j is the value at t_last of the line fitted to the observed speeds, clamped to
///   [0, `largest_input_speed`];
/// - the position is the last observed one;
/// and then propagated by CTRV from t_last to `now` (≥ t_last). Static obstacles: the last pose,
/// speed and yaw rate 0.
motion_estimate estimate_motion(const obstacle_track& track, double history_window, double now);

/// How many of the last observations of `track` `estimate_motion` reads: those within
/// [t_last − history_window, t_last], at least the last two; the last one of a static obstacle.
/// A history that ends with those observations gives the same estimate. Needs a non-empty history.
std::size_t observations_read(const obstacle_track& track, double history_window);

/// Forecast pose at time t ≥ 0 after the estimate, with forecast time τ [s] (spec §4): constant
/// turn rate and velocity (CTRV) for t ≤ τ, then straight with the velocity vector reached at τ.
/// τ = 0 is straight-line extrapolation; τ ≥ t trusts the turn rate the whole way.
pose forecast_pose(const motion_estimate& motion, double forecast_time, double t);

}  // namespace mm
