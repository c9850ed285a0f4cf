#pragma once

#include <cstddef>
#include <span>

#include "mm/capture.hpp"

namespace mm::bench {

/// A benchmark input: where it is taken from and why.
struct captured_input {
  const char* name;              ///< benchmark argument label, e.g. "obstacles:1"
  std::size_t interacting;       ///< interacting obstacles at that instant (maneuvermap_capture)
  capture::capture_point point;  ///< scenario, overrides, agent, time
  const char* why;               ///< how the instant was chosen
};

/// The fixed planner inputs of the `plan/...` benchmarks, in order of obstacle count.
std::span<const captured_input> captured_inputs();

/// The captured input with `interacting` interacting obstacles.
const captured_input& captured(std::size_t interacting);

/// The costliest planning step of S3 (one interacting obstacle), next to the least room of
/// `captured(1)`: the `plan_costliest` case.
const captured_input& costliest_one_obstacle();

/// A planning input saved with `maneuvermap_capture --save`: replaying it would simulate too long.
struct saved_input {
  const char* file;  ///< JSON file, relative to the source tree
  const char* why;   ///< how the instant was chosen
};

/// A plan in the dense traffic of the 50-vehicle roundabout, late in the run, where it is costliest:
/// the `plan_following` and `planner_following` cases.
const saved_input& dense_following();

}  // namespace mm::bench
