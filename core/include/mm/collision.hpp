#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "mm/forecast.hpp"
#include "mm/maneuver.hpp"

namespace mm {

/// An obstacle ready for collision tests: its motion estimate and footprint.
struct forecast_obstacle {
  motion_estimate motion;
  footprint shape;
};

/// The time window of the collision test (spec §5).
struct collision_window {
  double horizon = 1.0;    ///< T_h [s]: the maneuver's duration, then straight ahead
  double duration = 3.0;   ///< T_c [s] ≥ T_h
  double time_step = 0.05; ///< sampling step [s] of [0, T_c]
  double margin = 0.0;     ///< safety margin inflating every obstacle [m] (spec §2)
};

inline constexpr double no_collision = std::numeric_limits<double>::infinity();

/// The sample times k·step, k = 0..K, of [0, duration], the last one equal to `duration`.
std::vector<double> sample_times(double duration, double step);

/// Largest time step [s] at which the ego and `obstacle` cannot pass through each other between
/// samples (spec §5): the smallest footprint dimension over the largest relative speed within the window.
double tunneling_time_step(const ego_state& ego, const forecast_obstacle& obstacle,
                           const collision_window& window);

/// The first sample time at which the ego executing `u` overlaps one of `obstacles`, obstacle j
/// following its forecast with forecast time `forecast_times[j]`; `no_collision` if none (spec §5).
double first_collision_time(const ego_state& ego, const maneuver& u,
                            std::span<const forecast_obstacle> obstacles,
                            std::span<const double> forecast_times, const collision_window& window);

/// True when `first_collision_time` is finite: the maneuver collides [CSS].
bool maneuver_collides(const ego_state& ego, const maneuver& u,
                       std::span<const forecast_obstacle> obstacles,
                       std::span<const double> forecast_times, const collision_window& window);

/// Time to collision [s] (spec §6): first time the ego holding `nominal` (its §5 trajectory)
/// overlaps `obstacle` following its CTRV forecast for the whole window; `no_collision` if none
/// within T_c. Located on the window's time samples, then refined by bisection to 1e-4 s.
double time_to_collision(const ego_state& ego, const maneuver& nominal,
                         const forecast_obstacle& obstacle, const collision_window& window);

}  // namespace mm
