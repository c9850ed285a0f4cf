#pragma once

#include <cstdint>
#include <optional>

#include "mm/commonroad/scenario.hpp"
#include "mm/maneuver.hpp"
#include "mm/planner_config.hpp"
#include "mm/sim/scenario.hpp"

namespace mm::commonroad {

/// How a recording is replayed with one of its road users driven by the planner (docs/commonroad.md).
struct replay_options {
  std::uint32_t agent = 0;  ///< the road user the planner drives: a vehicle with a rectangular footprint
  planner_config config;    ///< its planner (spec §4–§9)
  /// Its limits (spec §3); the speed cap is raised to its largest recorded speed where that is higher.
  ego_limits limits;
  /// v_des [m/s] of its speed keeping; none: its recorded speed at the same time (the driver's own
  /// speed, as the desired speed profile of the planning vehicle).
  std::optional<double> desired_speed;
  /// false: it follows its recorded path at its desired speed without planning (the baseline).
  bool avoidance = true;
  /// The road constraint (spec §5) on the lanelets: the replay's drivable area is their union
  /// (`lanelet_polygons`), which the planned road user keeps to within T_h while it is on it.
  bool on_lanelets = false;
  /// Reactive replay: every other moving vehicle (a rectangle) keeps its distance to the road user
  /// ahead on its recorded path, lagging behind its recording where it must and never ahead of it
  /// (`sim::scripted_car_following`, docs/commonroad.md; `reactive_traffic()` is the usual choice);
  /// none: they replay their recordings exactly. Pedestrians (discs) do not react.
  std::optional<sim::scripted_car_following> reactive;
};

/// Car following for a reactive replay: the defaults of `sim::scripted_car_following`, following
/// only road users that do not keep to their recordings (the driven one, and those held up by it in
/// turn): the recorded road users' interactions with each other are in the recording, and recorded
/// drivers keep shorter gaps than the defaults' (driving car 1214 of USA_Lanker-1_1 for its 4 s,
/// 11 other cars fall up to 8.8 m behind their recordings when they follow whatever is ahead; one,
/// car 1216, when they follow only the road users that deviate).
sim::scripted_car_following reactive_traffic();

/// The recording as a simulation (closed loop for one road user, the others replayed):
/// - the road user `options.agent` becomes a planning vehicle whose reference path is the polyline
///   through its recorded positions; it enters at its first recorded step with its recorded speed
///   and then follows that path with the planner, keeping the speed it had at the same time in the
///   recording (or a given constant one);
/// - every other road user replays its recording exactly at the recorded steps (linearly between
///   them, along the polyline of its positions, at the speed that covers each piece in one step),
///   entering at its first step and leaving after its last (one that never moves stands there for
///   its recorded steps); a rectangle becomes a scripted vehicle, a disc a pedestrian;
/// - static obstacles keep their footprint (a disc as the 16-gon around it).
/// The run lasts until the last recorded step, at the simulator's 100 Hz. The replayed road users do
/// not react to the planned one unless `options.reactive` is set. Throws `measure_error` naming the
/// road user that cannot be replayed (not a vehicle, a footprint that is neither a rectangle nor a
/// disc) and why.
sim::scenario replay_scenario(const scenario& s, const replay_options& options);

/// The name a road user gets in a replay: its type and id, e.g. `car-34`.
std::string replay_name(const obstacle& o);

}  // namespace mm::commonroad
