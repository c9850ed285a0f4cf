#pragma once

namespace mm {

/// The magnitudes a planning input may have besides being finite (`validation_error`), far beyond
/// any road user's: within them every square, product and sum the planner forms stays finite, so no
/// input it accepts can make a NaN (docs/method.md §5, item 18). Found by fuzzing the planner
/// (`fuzz/planner_fuzzer.cpp`): a turning radius of 5e-324 m made NaN indices, and a given yaw rate
/// of 1e308 rad/s undefined behaviour; the other bounds keep the same squares and products finite.
inline constexpr double largest_input_coordinate = 1e8;        ///< |x|, |y| of a position [m]
inline constexpr double largest_input_speed = 1e3;             ///< a speed cap, an observed or given speed [m/s]
inline constexpr double largest_input_yaw_rate = 1e2;          ///< a given yaw rate; estimates are clamped to it [rad/s]
inline constexpr double largest_input_acceleration = 1e3;      ///< a_max, d_max, a_lat_max [m/s²]
inline constexpr double smallest_input_turning_radius = 1e-3;  ///< R_min [m]: 1/R_min stays finite
inline constexpr double largest_input_safety_margin = 1e3;     ///< [m]
inline constexpr double largest_observation_age = 1e3;         ///< planning time − an obstacle's last observation [s]
/// A rectangle's length and width, a disc's radius, the coordinates of a polygon's vertices [m].
inline constexpr double largest_footprint_size = 1e3;

}  // namespace mm
