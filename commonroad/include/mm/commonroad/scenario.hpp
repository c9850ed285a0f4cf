#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mm/drivable_area.hpp"
#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm::commonroad {

/// One recorded state of a road user (docs/commonroad.md; CommonRoad `initialState` or a
/// trajectory `state`, always `<exact>` values).
struct state {
  std::int64_t step = 0;               ///< time step k; the time is k · `scenario::time_step` [s]
  vec2 position;                       ///< centre of the shape [m]
  double orientation = 0.0;            ///< yaw [rad], counter-clockwise from +x, as in the file (not wrapped)
  double velocity = 0.0;               ///< speed along the orientation [m/s]; recordings give small negatives
  std::optional<double> yaw_rate;      ///< [rad/s], when the file gives it
  std::optional<double> acceleration;  ///< [m/s²], when the file gives it

  friend bool operator==(const state&, const state&) = default;
};

enum class obstacle_role : std::uint8_t { dynamic_obstacle, static_obstacle };

/// A road user or a static obstacle of the file: 2020a `dynamicObstacle` / `staticObstacle`, or a
/// 2018b `obstacle` with its `role`.
struct obstacle {
  std::uint32_t id = 0;
  obstacle_role role = obstacle_role::dynamic_obstacle;
  std::string type;     ///< the file's `type`: car, truck, bus, motorcycle, bicycle, pedestrian, parkedVehicle, …
  /// Relative to the state's position and orientation: a rectangle or disc centred there, or a
  /// convex polygon in the body frame (a rectangle or circle the file offsets from the centre).
  footprint shape;
  /// The initial state, then the trajectory's states, at consecutive steps (a static obstacle: one).
  std::vector<state> states;

  friend bool operator==(const obstacle&, const obstacle&) = default;
};

/// A lane of the road network: its two bounds, in the driving direction, and its links.
struct lanelet {
  std::uint32_t id = 0;
  std::vector<vec2> left_bound;   ///< [m]
  std::vector<vec2> right_bound;  ///< [m]
  std::vector<std::uint32_t> predecessors;  ///< ids of the lanelets it continues, as the file gives them
  std::vector<std::uint32_t> successors;    ///< ids of the lanelets that continue it

  friend bool operator==(const lanelet&, const lanelet&) = default;
};

/// The start of an ego task of the file (its goal is not read).
struct planning_problem {
  std::uint32_t id = 0;
  state initial;

  friend bool operator==(const planning_problem&, const planning_problem&) = default;
};

/// What a CommonRoad scenario file holds, as far as measuring road users needs it.
struct scenario {
  std::string benchmark_id;  ///< the root's `benchmarkID`
  std::string version;       ///< `commonRoadVersion`: "2018b" or "2020a"
  std::string date;          ///< the root's `date` when it is one (`is_date`), else empty
  double time_step = 0.1;    ///< `timeStepSize` [s], > 0
  std::vector<lanelet> lanelets;
  std::vector<obstacle> obstacles;  ///< in file order; ids unique among them
  std::vector<planning_problem> planning_problems;

  friend bool operator==(const scenario&, const scenario&) = default;
};

/// Whether `text` is a calendar date written YYYY-MM-DD (month 01–12, day 01–31), the form of the
/// root's `date`.
bool is_date(std::string_view text);

/// The lanelets as polygons, each its left bound then its right bound backwards: their union is the
/// road network, the drivable area of a measurement or a replay on the lanelets (spec §5's road
/// constraint; `mm::drivable_area`). Each lanelet's start and end are open edges: where no other
/// lanelet continues it, the road leads on beyond the recording's map. Throws
/// `std::invalid_argument` naming the lanelet whose bounds enclose no area.
drivable_outline lanelet_polygons(const scenario& s);

/// The corners [m] of `shape` at the recorded state `x`, in the world: a rectangle's or a convex
/// polygon's, placed at x's position and orientation; a disc as the regular 16-gon around it
/// (never smaller than the disc). How a static obstacle becomes a polygon in a replay's scenario
/// and in the scene.json of a measurement.
std::vector<vec2> world_polygon(const footprint& shape, const state& x);

}  // namespace mm::commonroad
