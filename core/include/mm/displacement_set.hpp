#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "mm/maneuver.hpp"

namespace mm {

/// The two maneuver families (spec §3): brake-and-steer [AS−] (a ≤ 0) and
/// accelerate-and-steer [AS+] (a ≥ 0).
enum class family : std::uint8_t { brake, accelerate };

std::string_view to_string(family f);

/// Sampling of a displacement set: a grid of nodes in (a, κ).
struct sampling_resolution {
  std::size_t accelerations = 14;  ///< nodes per family in a (≥ 2), from the limit to a = 0
  std::size_t curvatures = 19;     ///< nodes in κ (≥ 1), from −κ_max to κ_max

  friend bool operator==(const sampling_resolution&, const sampling_resolution&) = default;
};

/// Area element of the end-point map (s, κ) ↦ arc_point(κ, s) (spec §3):
/// dA = (1 − cos κs)/κ² · ds · dκ [m], → s²/2 as κ → 0.
double area_element(double arc_length, double curvature);

/// G(s, κ) = ∫₀ˢ area_element(σ, κ) dσ = (s − sin(κs)/κ)/κ² [m²], → s³/6 as κ → 0.
double area_element_primitive(double arc_length, double curvature);

/// One sampled maneuver of a family and the area of the displacements it stands for.
struct displacement_sample {
  maneuver u;
  vec2 end_point;            ///< displacement: end of the arc at T_h, ego frame (x forward) [m]
  double area_weight = 0.0;  ///< area of its grid cell in the end-point plane [m²] (see `displacement_set::area`)
};

/// A sampled available displacement set [AS−] or [AS+] (spec §3).
///
/// Node (i_a, i_κ) is sample `i_a * curvature_count + i_κ`. Its weight is the exact integral of
/// the area element over its cell (the half-way lines to the neighbouring nodes, clipped to the
/// family's bounds), so the weights sum to `area`. Two closings of the spec, see docs/method.md:
/// - without steering (κ_max = 0) the set is a segment of zero area; weights are then the limit
///   of the area ratio as κ_max → 0, i.e. ∫ s²/2 ds per cell (units m³), which keeps MI continuous;
/// - when every maneuver ends at the same point (area 0, e.g. [AS−] at standstill) the set is
///   `degenerate` and all samples weigh the same, so MI is 1 if that displacement is safe, else 0.
struct displacement_set {
  family fam = family::brake;
  double min_acceleration = 0.0;  ///< [m/s²]
  double max_acceleration = 0.0;  ///< [m/s²]
  double max_curvature = 0.0;     ///< κ_max(v0) [1/m]
  double area = 0.0;              ///< area(AS±) [m²], 0 when degenerate
  bool degenerate = false;
  std::size_t acceleration_count = 0;
  std::size_t curvature_count = 0;
  std::vector<displacement_sample> samples;
  /// Areas of the cells *between* neighbouring nodes, for interpolating estimators: cell (i, j)
  /// spans nodes i..i+1 in a and j..j+1 in κ, index i·(curvature_count − 1) + j; with a single
  /// curvature node, cell i spans nodes i..i+1 and the whole κ range. They sum to `area`.
  std::vector<double> cell_weights;
};

/// Row `row`'s acceleration [m/s²] were the rows of `set` evenly spaced in a over
/// [min_acceleration, max_acceleration]: what they are where the arc length is affine in a, bit for
/// bit (`available_displacements`), and independent of the speed.
double evenly_spaced_acceleration(const displacement_set& set, std::size_t row);

/// The sampled set of displacements reachable with maneuvers of `fam` within `horizon` [T_h, s]
/// from speed `initial_speed` [m/s] (spec §3). Without `node_weights` (the interpolating indices
/// read only `cell_weights`) every node's `area_weight` is 0 and `area` is the sum of the cell
/// weights, which saves half the work. Without `end_points` (what only drawings read) every
/// `end_point` is (0, 0), which saves a sine and a cosine per node.
displacement_set available_displacements(double initial_speed, const ego_limits& limits,
                                         double horizon, family fam,
                                         const sampling_resolution& resolution, bool node_weights = true,
                                         bool end_points = true);

}  // namespace mm
