#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mm/collision.hpp"
#include "mm/collision_sets.hpp"
#include "mm/drivable_area.hpp"
#include "mm/maneuver.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// The optional road constraint of spec §5: a maneuver whose swept footprint leaves the drivable
/// area within T_h is unsafe in both families. It binds an ego that starts on the area
/// (`starts_on_drivable_area`); such an ego leaves the area exactly when its footprint touches the
/// area's boundary, so a maneuver's *road clearance* is the smallest signed distance of its footprint
/// to the boundary over the road's sample times (`road_sample_times`), clamped to ±cap: ≤ 0 ⇔ the
/// maneuver leaves the road (docs/method.md §5).

/// The road constraint's sample times [s]: the collision window's sample times (`sample_times(T_c,
/// Δ)`) before T_h, and T_h. The window's step is below the ego's own tunneling bound
/// (`road_time_step`), so a footprint cannot cross a boundary segment between two of them.
std::vector<double> road_sample_times(const collision_window& window);

/// Longest step at which the ego's footprint cannot pass over a boundary segment between two
/// sample times [s]: its smallest dimension over its top speed within T_h, the tunneling bound of
/// spec §5 (`tunneling_time_step`) with an obstacle that stands still and has no width.
double road_time_step(const ego_state& ego, const collision_window& window);

/// True when the constraint binds the ego: its reference point lies in the area and its footprint
/// is clear of the boundary (a positive `boundary_clearance`). An ego off the road, or on its edge,
/// is not constrained by it.
bool starts_on_drivable_area(const drivable_area& area, const ego_state& ego);

/// Road clearance of maneuver `u` [m]: min over `road_sample_times` of the footprint's
/// `boundary_clearance`, clamped to [−cap, cap].
double road_clearance(const drivable_area& area, const ego_state& ego, const maneuver& u,
                      const collision_window& window, double cap);

/// The reference for `road_field`: `road_clearance` of every maneuver, each sample time and boundary
/// segment asked.
clearance_set road_clearances_reference(const drivable_area& area, const ego_state& ego,
                                        std::span<const maneuver> maneuvers, const collision_window& window,
                                        double cap);

/// True when the footprint of the ego executing `u` stays clear of the boundary over the whole of
/// [0, T_h], not only at sample times: conservative advancement, as `verified_collision_free` — the
/// boundary clearance changes no faster than the largest point speed L, so from a clearance c > 0 at
/// t none is lost before t + c/L; a step shorter than `resolution` [s] counts as not proven, unless it
/// reaches T_h.
bool stays_on_drivable_area(const drivable_area& area, const ego_state& ego, const maneuver& u,
                            const collision_window& window, double resolution = 1e-3);

/// The reference for `stays_on_drivable_area`: the boundary clearance at every multiple of
/// `resolution` [s] in [0, T_h] and at T_h, each > 0.
bool stays_on_drivable_area_reference(const drivable_area& area, const ego_state& ego, const maneuver& u,
                                      const collision_window& window, double resolution);

/// The road clearances of a sweep's samples, fast (the road's `clearance_field`). The boundary does
/// not move, and before T_h a sample's placement depends only on its curvature κ and the arc length
/// s it has travelled (`arc_placement`), so the samples of one column (one κ) pass through the same
/// placements, each at its own arc lengths s(t_r; a). Along that arc the road clearance is
/// L-Lipschitz in s, L = 1 + |κ| R (R the footprint's bounding radius): a clearance c found at s
/// proves every arc length within |c|/L of s clear (c > 0) or off the road (c ≤ 0). Which samples
/// leave the road is decided column by column: each (sample, road time) whose arc length no proof
/// covers is asked, and proves the stretch about it; a sample's first position off the road decides
/// it. Values are computed only where asked (`exact`), the times whose arc lengths the clearances
/// found bound above the smallest so far left out; equal bit for bit to `road_clearances_reference`,
/// sign and value; elsewhere the set holds ±cap by the sign. Requires an ego that starts on the area.
class road_field {
 public:
  road_field(const ego_sweep& sweep, const drivable_area& area, double cap);

  /// True when some sample leaves the road.
  bool collides() const { return !collisions_.none(); }
  /// The samples whose road clearance is ≤ 0.
  const sample_mask& collisions() const { return collisions_; }
  /// Per sample: its road clearance where made exact, else ±cap by its sign.
  std::span<const double> set() const { return values_; }
  bool is_exact(std::size_t m) const { return exact_[m] != 0; }
  /// Sample m's road clearance, `road_clearances_reference` bit for bit; kept in `set()`.
  double exact(std::size_t m);

  /// Boundary segments near enough to matter, and the tests made (for the plan's work counts).
  std::size_t near_segments() const { return near_.size(); }
  std::size_t bound_checks() const { return bound_checks_; }

 private:
  /// A stretch [lo, hi] of arc length [m] along one column's arc, proven clear of the boundary or
  /// across it (`off`) at every arc length in it.
  struct proven {
    double lo;
    double hi;
    bool off;
  };
  /// Decides which samples leave the road, column by column.
  void decide();
  static void add_proof(std::vector<proven>& proofs, proven p);
  /// A road clearance found at an arc length of one column's arc (capped at the field's cap).
  struct evaluation {
    double arc_length;  ///< [m]
    double clearance;   ///< [m]
  };
  /// Orders evaluations by arc length: `std::upper_bound` of arc length s.
  static bool before(double s, const evaluation& e) { return s < e.arc_length; }
  /// Lower bound of the road clearance at arc length s of a column [m], from the evaluations found
  /// there (in order of arc length) and the column's Lipschitz constant; −∞ without any.
  static double lower_bound_at(const std::vector<evaluation>& found, double s, double lipschitz);
  placement at(std::size_t r, std::size_t m) const;

  const ego_sweep& sweep_;
  double cap_;
  std::vector<segment_line> near_;
  /// The footprint's bounding radius about its reference point, rounded up [m]: no point of the
  /// footprint is farther from it.
  double footprint_radius_ = 0.0;
  std::size_t sampled_times_ = 0;  ///< the sweep's sample times before T_h; road time r = sampled_times_ is T_h
  sample_mask collisions_;
  std::vector<double> values_;
  std::vector<std::uint8_t> exact_;
  std::vector<std::vector<proven>> proofs_;  ///< `decide`'s: per column, in order
  /// Per sample its row (acceleration) and column (curvature); per row and road time the arc length
  /// [m]; per column the Lipschitz constant 1 + |κ| R of the clearance in the arc length, and the
  /// clearances `decide` found, in order of arc length.
  std::vector<std::uint32_t> row_of_;
  std::vector<std::uint32_t> column_of_;
  std::vector<double> arc_;
  std::vector<double> lipschitz_;
  std::vector<std::vector<evaluation>> evaluations_;
  std::vector<segment_line> candidates_;  ///< `exact`'s scratch: the segments near one sample's path
  std::size_t bound_checks_ = 0;
};

}  // namespace mm
