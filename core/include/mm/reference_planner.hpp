#pragma once

#include "mm/planner.hpp"

namespace mm {

/// Resolution of the reference planner.
struct reference_resolution {
  sampling_resolution sampling{41, 121};  ///< dense (a, κ) grid per family
  /// Time resolution of the continuous-time collision proof [s]: a sample passing within
  /// (largest relative point speed × this) of an obstacle, ≈ 2.5 mm, counts as colliding.
  double proof_resolution = 1e-4;
  /// Accelerations per family where the ego cannot steer (κ_max = 0, the one-dimensional case of
  /// spec §10): each family is a segment, and `sampling`'s 41 nodes along it leave the reference's
  /// own error near the bound (0.021 against 641 nodes in S1 without steering at 2.73 s).
  std::size_t one_dimensional_accelerations = 641;
};

/// The (a, κ) grid per family the reference planner samples for an ego with these limits:
/// `resolution.sampling`, or `one_dimensional_accelerations` × 1 without steering.
sampling_resolution reference_grid(const ego_limits& limits, const reference_resolution& resolution);

/// The slow, obviously-correct reference of `plan` (spec §11): a dense grid of maneuvers, each
/// tested on its own against each obstacle and forecast time for the whole window in continuous
/// time (`verified_collision_free`: conservative advancement, exact up to `proof_resolution`),
/// MI as the safe samples' share of the area, and the exhaustive forecast-time search for several
/// obstacles, on `reference_grid(input.ego.limits, resolution)`. `input.config.resolution`,
/// `max_time_step` and `assignment_search` are ignored.
plan_result plan_reference(const plan_input& input, const reference_resolution& resolution = {});

}  // namespace mm
