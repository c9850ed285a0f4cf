#pragma once
// A simulation run as a CommonRoad recording (`maneuvermap run --commonroad FILE.xml`,
// docs/commonroad.md "A run as a CommonRoad recording").
#include <cstdint>
#include <vector>

#include "mm/commonroad/scenario.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::cli {

/// Collects the states of every agent of a run at the times k·`time_step` into a CommonRoad
/// scenario (`mm::commonroad::scenario`, written by `mm::commonroad::write_scenario`):
/// - each agent an obstacle with id = its simulator id + 1: planning and scripted vehicles as
///   `dynamicObstacle`s of type `car` (their rectangles), pedestrians of type `pedestrian` (discs),
///   static obstacles as `staticObstacle`s of type `unknown` (their polygons about the mean of their
///   vertices);
/// - a state per recorded time while the agent is present: its reference point, heading, speed,
///   acceleration and yaw rate (speed × curvature), over the steps of its first stretch of presence;
/// - each planning vehicle also a planning problem with its obstacle's id and first state;
/// - the scenario's roads as lanelets, one per piece of a road's centre line, `width` wide, each the
///   successor of the piece before it; and its roundabout's lanes (`mm::sim::roundabout_lane_edges`:
///   the ring's pieces between its junctions, an entry and an exit lanelet per arm, with their
///   links) as wide as in its drivable area, else 3.5 m (half the widest lane the ring can have when
///   that is narrower); a drivable area of other polygons is not written.
class commonroad_recording {
 public:
  /// Throws `input_error` unless `time_step` [s] is a whole multiple of the run's time step.
  commonroad_recording(const scenario_file::loaded_scenario& loaded, double time_step);

  /// Records `now` when its time is on the recording's grid; call it at every step.
  void record(const mm::sim::simulation& now);

  /// The recording so far.
  mm::commonroad::scenario scenario() const;

 private:
  const scenario_file::loaded_scenario* loaded_;
  double time_step_;
  std::size_t stride_;  ///< simulation steps per recorded step
  std::vector<mm::commonroad::obstacle> obstacles_;
  std::vector<bool> ended_;  ///< an agent's first stretch of presence is over
  bool started_ = false;
};

}  // namespace mm::cli
