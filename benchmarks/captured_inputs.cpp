#include "captured_inputs.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace mm::bench {

std::span<const captured_input> captured_inputs() {
  static const std::vector<captured_input> inputs{
      {"obstacles:0", 0, {"s3-left-turn", {}, "A", 1.0}, "S3 before B comes within reach"},
      {"obstacles:1", 1, {"s3-left-turn", {}, "A", 4.80}, "S3, least room of the run (B turning across A)"},
      {"obstacles:2", 2, {"s6-busy-roundabout", {}, "N01", 5.44},
       "S6, N01's least room among its plans with two interacting neighbours (15 relevant)"},
      {"obstacles:4", 4, {"s6-busy-roundabout", {}, "E02", 7.63},
       "S6, E02's least room among its plans with four interacting neighbours (18 relevant)"},
      {"obstacles:8", 8, {"s7-crosswalk-crowd", {}, "A", 4.10},
       "S7, least room among plans with eight interacting pedestrians (A reaching the crosswalk)"},
  };
  return inputs;
}

const captured_input& captured(std::size_t interacting) {
  for (const captured_input& c : captured_inputs()) {
    if (c.interacting == interacting) return c;
  }
  throw std::out_of_range("no captured input with " + std::to_string(interacting) + " interacting obstacles");
}

const captured_input& costliest_one_obstacle() {
  static const captured_input input{
      "obstacles:1", 1, {"s3-left-turn", {}, "A", 4.70},
      "S3, its costliest step (B driving towards A's path before it turns across it): the most "
      "instructions of the plans from 4.68 to 4.74 s (callgrind; at 15 x 21 the step at 4.71 s, "
      "also the slowest of every run of maneuvermap run s3-left-turn --timing)"};
  return input;
}

const saved_input& dense_following() {
  static const saved_input input{
      "benchmarks/inputs/s6-e09-16.94s.json",
      "S6 at 16.94 s: E09 in the ring, 6.5 m behind the car it follows (centre to centre), 38 of its 39 "
      "neighbours relevant; a typical plan of the run's dense seconds (16 to 18 s: median 3.5 ms with two "
      "threads in maneuvermap run s6-busy-roundabout --jobs 2 --timing; this one 5.0 ms). Saved with "
      "maneuvermap_capture s6-busy-roundabout --agent E09 --at 16.94 --save FILE (100 s to simulate there)"};
  return input;
}

}  // namespace mm::bench
