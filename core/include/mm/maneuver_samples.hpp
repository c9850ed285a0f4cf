#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mm/displacement_set.hpp"

namespace mm {

/// A half-open range [begin, end) of sample indices.
struct index_range {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};

/// Every maneuver the planner evaluates at one planning step (spec §3, §8), in this order:
/// the sampled [AS−], the sampled [AS+], then the nominal-curvature columns of both families
/// (κ = κ_nom on each family's acceleration nodes). The columns weigh nothing in the indices; they
/// answer "is there a safe maneuver with κ = κ_nom" (urgent steering, §8.3) and are candidates too.
struct maneuver_samples {
  displacement_set brake;
  displacement_set accelerate;
  double nominal_curvature = 0.0;  ///< κ_nom, within the limits [1/m]
  std::vector<maneuver> maneuvers;
  std::vector<family> families;
  std::vector<double> area_weights;  ///< [m²]; 0 on the nominal-curvature columns
  std::vector<vec2> end_points;      ///< displacements, ego frame [m]

  std::size_t size() const { return maneuvers.size(); }
  /// The weighted grid of a family.
  index_range grid(family f) const;
  /// The nominal-curvature column of a family.
  index_range nominal_column(family f) const;
  /// area(AS±) as the sum of the family's weights (equal weights summing to 1 when degenerate).
  double total_weight(family f) const;
  const displacement_set& set(family f) const { return f == family::brake ? brake : accelerate; }
};

/// Samples both families of `ego` at `resolution` over the displacement horizon [T_h, s], and the
/// nominal-curvature columns for `nominal_curvature` (clamped to ±κ_max). `node_weights` and
/// `end_points`: see `available_displacements` (without them `area_weights` are all 0, and
/// `end_points` all (0, 0)).
maneuver_samples sample_maneuvers(const ego_state& ego, double nominal_curvature, double horizon,
                                  const sampling_resolution& resolution, bool node_weights = true,
                                  bool end_points = true);

/// Rewrites the nominal-curvature columns of `samples` (made by `sample_maneuvers` for an ego of
/// the same speed and limits, and the same horizon) for `nominal_curvature`: the result equals
/// `sample_maneuvers(ego, nominal_curvature, horizon, ...)` with the same flags, bit for bit.
void set_nominal_curvature(maneuver_samples& samples, const ego_state& ego, double nominal_curvature, double horizon,
                           bool end_points = true);

}  // namespace mm
