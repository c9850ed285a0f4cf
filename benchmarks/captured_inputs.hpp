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

}  // namespace mm::bench
