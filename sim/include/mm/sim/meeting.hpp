#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "mm/geometry.hpp"
#include "mm/sim/path.hpp"

namespace mm::sim {

/// A timing constraint between two agents: "timed so that they collide if neither reacts"
/// (docs/simulator.md, the paper's scenarios). Each agent is taken to drive from its start to the
/// conflict point at its constant initial speed; `first` must reach it `lag` seconds before
/// `second` (0: at the same moment).
struct meeting {
  std::size_t first = 0;             ///< index into the agents of `meeting_start_times`
  std::size_t second = 0;            ///< another index, ≠ first
  double first_travel_time = 0.0;    ///< [s] ≥ 0 from `first`'s start to the conflict point
  double second_travel_time = 0.0;   ///< [s] ≥ 0 from `second`'s start to the conflict point
  double lag = 0.0;                  ///< arrival of `second` minus arrival of `first` [s], any sign
};

/// Travel time [s] over `distance` [m] ≥ 0 at constant `speed` [m/s] > 0. Throws
/// std::invalid_argument when the agent never gets there (speed 0, distance behind it).
double travel_time(double distance, double speed);

/// Arc length [m] of the point of `reference` nearest to `point`, which must lie within
/// `tolerance` [m] of it (the path's straight extensions beyond its ends do not count). Throws
/// std::invalid_argument, naming the distance, when it does not.
double arc_length_at(const path& reference, vec2 point, double tolerance);

/// Start times [s] that satisfy every meeting: arrival_i = start_i + travel_i, and
/// arrival_second − arrival_first = lag for each meeting. Agents linked by meetings (a connected
/// group) are shifted together so that none starts before its `start_times` entry and at least
/// one keeps it: for a single meeting, the start of the agent that would arrive earlier is
/// delayed (S3: "the start of one is delayed so that both reach the conflict point at the same
/// moment"). Agents in no meeting keep their start time.
///
/// Throws std::invalid_argument for an index out of range, an agent meeting itself, negative or
/// non-finite travel times, or meetings that contradict each other around a cycle (by more than
/// 1e-9 s). Pure: no I/O, same input, same output.
std::vector<double> meeting_start_times(std::span<const double> start_times, std::span<const meeting> meetings);

}  // namespace mm::sim
