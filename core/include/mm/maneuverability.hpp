#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// Maneuverability Index of a family (spec §6):
/// MI±(τ) = area(ASS±(τ)) / area(AS±) = Σ_{safe samples} w / Σ_{samples} w over the family's grid,
/// where the safe samples are those not in `colliding` [CSS±(τ)]. In [0, 1].
double maneuverability_index(const maneuver_samples& samples, family f, const sample_mask& colliding);

/// Both indices for one collision set.
struct maneuverability_pair {
  double brake = 1.0;       ///< MI−
  double accelerate = 1.0;  ///< MI+
};

maneuverability_pair maneuverability_indices(const maneuver_samples& samples, const sample_mask& colliding);

/// Excluded forecast times (spec §6): τ_i > TTC, except τ_0 = 0 which is never excluded.
std::vector<std::uint8_t> excluded_forecast_times(std::span<const double> forecast_times,
                                                  double time_to_collision);

}  // namespace mm
