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
/// t none is lost before t + c/L; a step shorter than `resolution` [s] counts as not proven.
bool stays_on_drivable_area(const drivable_area& area, const ego_state& ego, const maneuver& u,
                            const collision_window& window, double resolution = 1e-3);

/// The reference for `stays_on_drivable_area`: the boundary clearance at every multiple of
/// `resolution` [s] in [0, T_h] and at T_h, each > 0.
bool stays_on_drivable_area_reference(const drivable_area& area, const ego_state& ego, const maneuver& u,
                                      const collision_window& window, double resolution);

/// The road clearances of a sweep's samples, fast (the road's `clearance_field`): which samples leave
/// the road is decided with the sweep's tree of blocks — at a road sample time a block is clear, or
/// off the road whole (and then decided for good), when its centre's clearance is farther from 0
/// than the block's spread; its halves are asked only at the times left undecided, and only about
/// the boundary segments that can be nearest for one of their samples then.
/// Values are computed only where asked (`exact`), equal bit for bit to `road_clearances_reference`;
/// elsewhere the set holds ±cap by the sign. Requires an ego that starts on the area.
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
  /// Decides block b at the road times `times` (indices: the sweep's sample times, then T_h) against
  /// the segments `segments` (indices into `near_`): whole where its centre's clearance is farther
  /// from 0 than its spread, else by its halves, at the times left.
  void decide(std::uint32_t b, std::span<const std::uint32_t> times, std::span<const std::uint32_t> segments,
              std::size_t depth);
  placement at(std::size_t r, std::size_t m) const;
  double spread(std::uint32_t b, std::size_t r) const;

  const ego_sweep& sweep_;
  double cap_;
  std::vector<segment_line> near_;
  /// The footprint's bounding radius about its reference point, rounded up, and its square [m, m²]:
  /// no point of the footprint is farther from the centre.
  double footprint_radius_ = 0.0;
  double footprint_reach_squared_ = 0.0;
  std::size_t sampled_times_ = 0;  ///< the sweep's sample times before T_h; road time r = sampled_times_ is T_h
  sample_mask collisions_;
  std::vector<double> values_;
  std::vector<std::uint8_t> exact_;
  /// Per depth of the tree: the times and segments a block's halves are asked at, and its scratch.
  struct level {
    std::vector<std::uint32_t> times;
    std::vector<std::uint32_t> segments;
    std::vector<double> distances;  ///< [time · segments + segment] of the centre
    std::vector<double> reach;      ///< [time]: nearest + twice the spread
  };
  std::vector<level> levels_;
  std::vector<segment_line> candidates_;  ///< `exact`'s scratch: the segments near one sample's path
  std::size_t bound_checks_ = 0;
};

}  // namespace mm
