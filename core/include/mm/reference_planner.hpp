#pragma once

#include "mm/planner.hpp"

namespace mm {

/// Resolution of the reference planner.
struct reference_resolution {
  sampling_resolution sampling{41, 41};  ///< dense (a, κ) grid per family
  double time_step = 0.005;              ///< fine collision time step [s]
};

/// The slow, obviously-correct reference of `plan` (spec §11): a dense grid, a fine time step,
/// every (sample, forecast time, obstacle, time) pair tested exactly with no pruning or sharing,
/// and the exhaustive forecast-time search for several obstacles. `input.config.resolution`,
/// `max_time_step` and `assignment_search` are ignored.
plan_result plan_reference(const plan_input& input, const reference_resolution& resolution = {});

}  // namespace mm
