#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mm/drivable_area.hpp"
#include "mm/footprint.hpp"
#include "mm/maneuver.hpp"
#include "mm/planner_config.hpp"
#include "mm/sim/follower.hpp"
#include "mm/sim/path.hpp"
#include "mm/sim/scripted.hpp"

namespace mm::sim {

/// The sizes and speeds of road users that scenario files (docs/scenario-format.md) and CommonRoad
/// replays (docs/commonroad.md) accept: within them the planner's tunneling time step, the smallest
/// footprint dimension over the relative speed (spec §5), stays above its floor
/// `mm::smallest_collision_time_step`: 0.05 m over 200 m/s is 0.25 ms.
inline constexpr double smallest_road_user_size = 0.05;   ///< [m], a footprint's smallest dimension
inline constexpr double largest_road_user_speed = 100.0;  ///< [m/s]
/// Where road users may be, so that every observation of a valid scenario stays within what the
/// planner takes (±`mm::largest_input_coordinate`, 10⁸ m) for the whole run: paths within ±4·10⁷ m,
/// at most 5·10⁷ m of travel in the run (speed × duration), lateral start offsets of at most
/// 1000 m; the remaining 10⁷ m hold the sensing noise with room to spare.
inline constexpr double largest_path_coordinate = 4e7;  ///< |x|, |y| of every point of a path [m]
inline constexpr double largest_travel = 5e7;           ///< a road user's top speed × the duration [m]
inline constexpr double largest_lateral_offset = 1e3;   ///< |start_lateral_offset| [m]
/// The largest standard deviation of the sensing noise, of positions [m] and of speeds [m/s]: no
/// draw of it (Box–Muller on 53-bit uniforms, within 8.6 σ) takes an observation out of what the
/// planner takes (`mm::largest_input_speed`, `mm::largest_input_coordinate`).
inline constexpr double largest_noise_sd = 10.0;
/// The most time steps a run may take (duration / time_step): 10⁷, almost 28 hours at 100 Hz. A
/// longer run is refused rather than simulated for days, or its step count overflowed.
inline constexpr double largest_step_count = 1e7;
/// The most time steps a planning vehicle's history window may span (history_window / time_step):
/// 1000, 10 s at 100 Hz. Its tracks hold that many observations of every other agent, and a window
/// of 1000 s at microsecond steps would ask for terabytes.
inline constexpr double largest_history_steps = 1000.0;

/// Gaussian sensor noise on every observation a planning vehicle makes (spec §4): independent,
/// zero-mean, with these standard deviations. Zero (the default) is exact sensing.
struct sensing_noise {
  double position_sd = 0.0;  ///< σ of each position coordinate, x and y [m], ≥ 0
  double heading_sd = 0.0;   ///< σ of the heading [rad], ≥ 0
  double speed_sd = 0.0;     ///< σ of the speed [m/s], ≥ 0

  friend bool operator==(const sensing_noise&, const sensing_noise&) = default;
};

/// A vehicle that follows its reference path and avoids the others with `mm::plan` (the ego A of
/// the paper; any number of them). It starts on its path at `start_arc_length`, displaced
/// `start_lateral_offset` to the left, heading along the path tangent.
struct planning_vehicle {
  std::string name;                      ///< unique among all agents, non-empty
  mm::sim::path path;                    ///< reference path, not empty
  double start_arc_length = 0.0;         ///< s0 [m], 0 ≤ s0 < path length
  double start_lateral_offset = 0.0;     ///< [m], positive to the left of the path
  double start_time = 0.0;               ///< [s] ≥ 0; before it the vehicle is absent or waits
  before_start_behaviour before_start = before_start_behaviour::absent;
  double initial_speed = 0.0;            ///< v at the start [m/s], 0 ≤ v ≤ limits.speed_cap
  double desired_speed = 0.0;            ///< v_des [m/s] ≥ 0: the cruise speed, not a cap (spec §3)
  /// When set, the desired speed changes over the run: v_des(t) = `profile_speed(*desired_speed_profile,
  /// t − start_time)` replaces `desired_speed` (e.g. the recorded speeds of a replayed driver).
  std::optional<speed_profile> desired_speed_profile;
  mm::rectangle shape;                   ///< footprint, spec §2 default 4.5 m × 1.8 m
  mm::ego_limits limits;                 ///< a_max, d_max, a_lat_max, R_min, v_cap (spec §3)
  /// Forecast policy, horizons, urgent steering, safety margin (spec §2–§9). With the default
  /// `safety_margin = 0` the planner grazes obstacles: see docs/simulator.md §12.
  mm::planner_config planner;
  follower_config follower;              ///< pure pursuit and speed keeping (u_nom, spec §8)
  /// false: apply u_nom without planning — the naive baseline that a scenario compares against.
  /// It still senses (so `simulation::planning_input` works) and is still crash-checked.
  bool avoidance = true;
  /// Plan every k-th simulation step (k ≥ 1), holding the last command in between.
  std::size_t planning_period = 1;

  friend bool operator==(const planning_vehicle&, const planning_vehicle&) = default;
};

/// A vehicle that replays `motion`, ignoring every other agent (the paper's B), or, with car
/// following, slowing behind the road user ahead on its path.
struct scripted_vehicle {
  std::string name;
  scripted_motion motion;
  mm::rectangle shape;  ///< footprint [m]
  /// Keeping a distance to the road user ahead, lagging behind `motion` where it must (an
  /// addition to spec §8); none: exactly `motion`, as the paper's B.
  std::optional<scripted_car_following> car_following;

  friend bool operator==(const scripted_vehicle&, const scripted_vehicle&) = default;
};

/// A pedestrian that replays `motion` (usually a constant speed and perhaps a stop at the kerb).
struct pedestrian {
  std::string name;
  scripted_motion motion;
  double radius = 0.35;  ///< disc footprint radius [m] (spec §2)

  friend bool operator==(const pedestrian&, const pedestrian&) = default;
};

/// A static obstacle: a convex polygon in world coordinates, 3 to `mm::max_polygon_vertices`
/// vertices, either orientation. Its reference point is the mean of its vertices.
struct static_obstacle {
  std::string name;
  std::vector<vec2> vertices;  ///< [m]

  friend bool operator==(const static_obstacle&, const static_obstacle&) = default;
};

/// Everything a run needs. Agents get ids in this order: planning vehicles, scripted vehicles,
/// pedestrians, static obstacles (see `simulation`).
struct scenario {
  std::string name;
  std::string description;
  double duration = 10.0;    ///< [s] > 0: the run ends at the first step time ≥ duration
  double time_step = 0.01;   ///< dt [s] > 0 (100 Hz as in the paper)
  std::uint64_t seed = 0;    ///< seeds the sensor noise
  sensing_noise noise;
  std::vector<planning_vehicle> planning_vehicles;
  std::vector<scripted_vehicle> scripted_vehicles;
  std::vector<pedestrian> pedestrians;
  std::vector<static_obstacle> static_obstacles;
  /// The drivable area (spec §5's optional road constraint): the union of these polygons, world
  /// frame [m], with their open edges (`mm::drivable_area`). Every planning vehicle that starts a
  /// step on it keeps its maneuvers on it within T_h. Empty: no road constraint.
  mm::drivable_outline drivable_area;

  friend bool operator==(const scenario&, const scenario&) = default;
};

/// The first problem of `s`, naming the agent and the field, e.g.
/// `planning_vehicles[0] "A": desired_speed = -1: expected a finite number ≥ 0 [m/s]`; or nothing.
std::optional<std::string> validation_error(const scenario& s);

/// Why `u` is not a command planning vehicle `v` can take at `speed` [m/s]: a ∈ [−d_max, a_max] and
/// |κ| ≤ κ_max(speed) (spec §3, `mm::max_curvature`), e.g. `acceleration = -9: expected from -7 to 3
/// [m/s²]`; or nothing.
std::optional<std::string> command_error(const planning_vehicle& v, double speed, const mm::maneuver& u);

/// The footprint of a static obstacle about its reference point (the mean of its vertices).
mm::convex_polygon static_footprint(const static_obstacle& obstacle);

/// The reference point of a static obstacle: the mean of its vertices [m].
vec2 static_reference_point(const static_obstacle& obstacle);

}  // namespace mm::sim
