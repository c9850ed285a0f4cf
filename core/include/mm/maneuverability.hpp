#pragma once

#include <array>
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

/// Share of the unit square where the clearance, interpolated bilinearly from its corner values,
/// is positive — the marching-squares polygon, with the centre value deciding saddles.
/// Corners: c00 at (0, 0), c10 at (1, 0), c01 at (0, 1), c11 at (1, 1).
double positive_fraction(double c00, double c10, double c01, double c11);

/// Share of [0, 1] where the linear interpolant of c0 (at 0) and c1 (at 1) is positive.
double positive_fraction(double c0, double c1);

/// One obstacle's clearances at the corners of a cell, counter-clockwise: (0, 0), (1, 0), (1, 1),
/// (0, 1) — along κ first, then along a (c00, c10, c11, c01 of `positive_fraction`).
using cell_corners = std::array<double, 4>;

/// Share of the unit square that is safe from every obstacle in `obstacles`: the intersection of
/// each obstacle's region where its interpolated clearance is positive. Each region is
/// `positive_fraction`'s polygon — the square cut by the segment between the crossings on its
/// edges (a saddle: by two, or two corner triangles when the centre value is ≤ 0) — so the
/// intersection of a few half-planes with the square, found by clipping. One obstacle:
/// `positive_fraction` of its corners, bit for bit; an obstacle ≤ 0 at every corner: 0.
/// Interpolating each obstacle on its own, not their minimum, keeps the boundary of the union of
/// the collision sets where each obstacle puts its own: a minimum of several clearances has kinks
/// between the nodes that a linear interpolant of it misses (docs/method.md §4.3).
double safe_fraction(std::span<const cell_corners> obstacles);

/// Share of [0, 1] safe from every obstacle, each interpolated linearly from its values at 0 and 1
/// (`positive_fraction`): the intersection of intervals. One obstacle: `positive_fraction`.
double safe_fraction(std::span<const std::array<double, 2>> obstacles);

/// Maneuverability Index from the signed clearances of the family's nodes (spec §6, the fast
/// estimator): MI = Σ_cells W_cell · positive_fraction(corners) / Σ_cells W_cell over the cells
/// between nodes (`displacement_set::cell_weights`). The safe/unsafe boundary is located between
/// nodes by linear interpolation instead of at the half-way line, which makes the error second
/// order in the node spacing. `clearance[k]` belongs to `set.samples[k]`; positive is safe. A
/// degenerate set counts its safe nodes.
double maneuverability_index(const displacement_set& set, std::span<const double> clearance);

/// Maneuverability Index of the safe set of several obstacles, AS \ ∪_j CSS_j (spec §6, §9), from
/// each obstacle's signed clearances (`clearances[j][k]`: obstacle j's clearance of
/// `set.samples[k]`, positive is safe): MI = Σ_cells W_cell · safe_fraction(the corners of the
/// obstacles with a corner ≤ 0) / Σ_cells W_cell — a cell where no obstacle has a corner ≤ 0 adds its
/// whole weight. With one obstacle equal, bit for bit, to `maneuverability_index(set, clearances[0])`;
/// with several, not the index of their minimum (see `safe_fraction`). A degenerate set counts the
/// nodes safe from every obstacle. The reference of the planner's indices with several obstacles,
/// which read only the corners of the cells where an obstacle's clearance changes sign.
double maneuverability_index_of_union(const displacement_set& set,
                                      std::span<const std::span<const double>> clearances);

/// `maneuverability_index_of_union` with each obstacle's signs also given as bits: `negative[j]`
/// holds, from index `first` on, one bit per node of `set` in node order, set where `clearances[j]`
/// is ≤ 0. Equal bit for bit; a cell where no obstacle has a corner ≤ 0 adds its weight, and one
/// that an obstacle is ≤ 0 at all four corners of adds nothing, without reading a value (grids of
/// 2 to 64 rows and columns; others go node by node). `single_shares` (empty, or one entry per
/// obstacle, each null or the obstacle's own array of the grid's cells, row by row): a cell that
/// obstacle j alone has a corner ≤ 0 at takes its safe share from `single_shares[j][cell]` when
/// that is not NaN and stores it there otherwise — for a caller that evaluates unions of the same
/// obstacles' clearances many times (the forecast-time search, spec §9). Such a share depends only
/// on the values at the ends of the cell's sign-changing edges (all four corners of a saddle), which
/// must be the same at every call that passes the array; the result is then the same bit for bit.
double maneuverability_index_of_union(const displacement_set& set,
                                      std::span<const std::span<const double>> clearances,
                                      std::span<const sample_mask> negative, std::size_t first,
                                      std::span<double* const> single_shares = {});

/// `maneuverability_index` from the signs of the clearances alone, as if every positive node were
/// +1 and every other −1: the boundary through the middle of every edge whose ends differ. Equal
/// bit for bit to `maneuverability_index` of such a ±c set, from a table of the 16 sign patterns of
/// a cell. What the fast forecast-time search ranks assignments by (docs/method.md §5).
double sign_index(const displacement_set& set, std::span<const double> clearance);

/// The samples whose values `maneuverability_index` reads beyond their signs, given which samples
/// are positive (`positive`, over every sample of `samples`): both ends of every edge of a
/// non-degenerate family's grid whose ends differ in sign. A cell whose corners share one sign
/// reads none; a saddle cell's four corners are all such ends. Into `read` (resized to the samples),
/// a grid row at a time on the mask's words (rows of up to 63 nodes; longer rows node by node).
void read_nodes(const maneuver_samples& samples, const sample_mask& positive, sample_mask& read);

/// The reference of `read_nodes`, node by node: the ends of every sign-changing grid edge and the
/// four corners of every saddle cell.
sample_mask read_nodes_reference(const maneuver_samples& samples, const sample_mask& positive);

/// `maneuverability_index` with the signs of `clearance` also given as bits: `positive` holds, from
/// index `first` on, one bit per node of `set` in node order, set where the clearance is > 0 (as the
/// planner's sample masks do, `first` being the family's first sample). Equal bit for bit; cheaper,
/// as the cells without a positive corner (which add nothing) are skipped by word operations.
double maneuverability_index(const displacement_set& set, std::span<const double> clearance,
                             const sample_mask& positive, std::size_t first);

/// `sign_index` from the signs alone, given as bits as above: equal bit for bit to `sign_index` of
/// any clearances with these signs.
double sign_index(const displacement_set& set, const sample_mask& positive, std::size_t first);

/// Excluded forecast times (spec §6): τ_i > TTC, except τ_0 = 0 which is never excluded.
std::vector<std::uint8_t> excluded_forecast_times(std::span<const double> forecast_times,
                                                  double time_to_collision);

}  // namespace mm
