#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "mm/planner.hpp"

namespace mm::testing {

/// What a random scene contains.
struct scene_options {
  std::size_t obstacles = 1;         ///< moving obstacles (vehicles and pedestrians)
  bool sensor_noise = false;         ///< add Gaussian noise to the observation histories
  bool allow_static = true;          ///< some obstacles may be static polygons
  double conflict_probability = 0.9; ///< share of obstacles aimed at the ego's path
};

/// A random planning step around a moving ego, its obstacles mostly timed to cross the ego's
/// path within the collision window, with histories generated from exact CTRV motion.
/// Deterministic for a given generator state.
plan_input random_scene(std::mt19937_64& rng, const scene_options& options = {});

/// A C++ description of `input` that reproduces it, printed when a randomized test fails.
std::string describe(const plan_input& input);

/// History of an obstacle moving with constant speed and yaw rate, ending at `now` in `current`:
/// `count` observations `step` apart.
std::vector<observation> ctrv_history(const pose& current, double speed, double yaw_rate, double now,
                                      std::size_t count = 51, double step = 0.01);

}  // namespace mm::testing
