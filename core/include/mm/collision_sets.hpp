#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "mm/collision.hpp"
#include "mm/maneuver.hpp"
#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"
#include "mm/translation.hpp"

namespace mm {

/// Signed distance − margin [m] between the ego executing `u` and the obstacle forecast with
/// forecast time `tau`, at time t.
double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window);

/// Signed clearance of every sample: the smallest signed distance − margin [m] between the ego
/// executing the sample and an obstacle over the collision window. Negative ⇔ the sample collides
/// [CSS]; the magnitude lets estimators place the boundary between samples. Clamped to ±cap.
///
/// Precisely, with d(t) the signed distance − margin: the window splits at the start t_s of its
/// straight part (`straight_part_start`: T_h for an obstacle that does not turn, else max(T_h, τ)),
/// from which both footprints go straight at constant velocities. Before it, d is sampled at the
/// sample times t_k < t_s (`sample_times`) and refined: min(min_k d_k, `refined_minimum` around the
/// argmin of those d_k). On [t_s, T_c] the relative motion is a translation and min d has a closed
/// form (`smallest_signed_distance`). The clearance is the smaller of the two: a value the signed
/// distance really takes (up to rounding), at or below every sampled one. Whether a sample collides
/// is decided by the sample times before t_s, the closed form after it (`clearance_field::collisions`)
/// and, next to a colliding sample, by this value (docs/method.md §4.4).
using clearance_set = std::vector<double>;

/// Most the signed distance of a pair whose points move at most at `rate` [m/s] (the sum of both
/// footprints' largest point speeds) can fall between a time and the nearest sample time [m]:
/// rate · step / 2, rounded up. A sampled minimum above it refines to a positive clearance.
double refinement_threshold(double rate, double time_step);

/// The ego's trajectories for every sample of a `maneuver_samples` over the collision window,
/// shared by all obstacles and forecast times of a planning step. Placements are computed lazily,
/// the first time a (sample, sample time) pair is asked for, and kept in the ego's frame, where they
/// depend only on the speed, the sample and the time: a restart with the same sample times keeps
/// them (but the nominal-curvature columns'), and each access rotates one into the world. On the
/// straight part (t > T_h) they cost no trigonometry. Every placement equals `maneuver_placement`
/// bit for bit.
///
/// The samples are also arranged in a tree of blocks (`block`): rectangles of neighbouring nodes of
/// a grid, halved along their longer side down to single samples, with a bound on how far apart
/// the placements of a block's samples can be at each sample time (`block_spread`). A collision
/// test of a block's centre sample then decides the whole block at once when its clearance is
/// farther from zero than that spread.
///
/// Holds mutable caches: one sweep must not be used by two threads at once.
class ego_sweep {
 public:
  ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window);

  /// The sweep of a new planning step whose ego differs from this one's in its pose and perhaps its
  /// speed (the limits, footprint radius and horizon equal), whose samples are the same object,
  /// with only the nominal-curvature columns rewritten (`set_nominal_curvature`) at the same speed,
  /// or sampled again at the new speed with the same resolution (a slow ego's rows follow the arc
  /// length and move with the speed), and whose window may differ in its duration, time step and
  /// margin: equal, bit for bit, to a new `ego_sweep(ego, samples, window)`, without building the
  /// tree of blocks again (its shape does not depend on the speed, `add_block`; at a new speed the
  /// blocks' extents are taken anew). Throws std::invalid_argument when what must be unchanged
  /// changed.
  void restart(const ego_state& ego, const collision_window& window);
  /// `restart(ego, window)` where it is possible, and true; else false, and the sweep is unchanged:
  /// where the limits, footprint radius or horizon changed, or the samples were taken at another
  /// resolution (told by the grids' rows and columns, even where the sample count is the same).
  bool try_restart(const ego_state& ego, const collision_window& window);

  const ego_state& ego() const { return ego_; }
  const maneuver_samples& samples() const { return samples_; }
  const collision_window& window() const { return window_; }
  std::size_t sample_count() const { return sample_count_; }
  const std::vector<double>& times() const { return times_; }

  /// Position [m] and heading direction (cos θ, sin θ) of a sample.
  using placement = mm::placement;
  /// Placement of sample m at time index k.
  placement at(std::size_t k, std::size_t m) const {
    const std::size_t index = placement_index(k, m);
    if (local_known_[index] != local_generation_) fill(k, m);
    const stored& p = local_[index];
    return in_world({{p.px, p.py}, {p.dx, p.dy}});
  }
  /// Placement of sample m at any time t [s]: `maneuver_placement` bit for bit, cheaper on the
  /// straight part.
  placement placement_at(std::size_t m, double t) const;
  /// World placements at time index k of the samples at tree-order positions [begin, end)
  /// (`order()`), as columns: `x[i]`, `y[i]` the reference point [m] and (`c[i]`, `s[i]`) the heading
  /// direction of position begin + i, equal bit for bit to `at(k, order()[begin + i])`. Laid out
  /// for the rasters' tests of a block's samples together; computed on first use at each start.
  struct placement_columns {
    const double* x;
    const double* y;
    const double* c;
    const double* s;
  };
  /// Positions that `skip` (indexed by tree-order position) holds are not computed: they hold the
  /// placement at the origin with heading +x, for the caller not to read.
  placement_columns ordered_placements(std::size_t k, std::size_t begin, std::size_t end,
                                       const sample_mask* skip = nullptr) const;
  /// The straight part of sample m after T_h: its reference point is `start + (t − T_h) velocity`.
  struct line {
    vec2 start;     ///< at T_h, world frame [m]
    vec2 velocity;  ///< [m/s]
  };
  line straight_line(std::size_t m) const {
    const straight_part& part = straight(m);
    return {part.start, part.velocity};
  }
  /// The heading direction of sample m on its straight part (t ≥ T_h), world frame.
  vec2 straight_direction(std::size_t m) const { return straight(m).direction; }
  /// Largest speed of sample m's reference point over the window [m/s].
  double sample_speed(std::size_t m) const { return sample_speed_[m]; }
  /// Largest speed of any point of the ego footprint executing sample m [m/s]: v_max (1 + |κ| R).
  double sample_point_speed(std::size_t m) const { return sample_point_speed_[m]; }

  /// Largest speed of any point of the ego footprint over the window [m/s]: v_max (1 + κ_max R).
  double largest_point_speed() const { return largest_point_speed_; }
  /// Largest speed of the ego's reference point over the window [m/s].
  double largest_speed() const { return largest_speed_; }
  /// A disc containing the reference points of all samples at time index k: about the start, of
  /// radius the farthest arc length travelled by then [m].
  vec2 reach_centre(std::size_t) const { return ego_.pose.position; }
  double reach_radius(std::size_t k) const { return reach_radius_[k]; }
  /// The same radius at any time t ≥ T_h [m]: `base` at T_h, growing at `rate` [m/s] (rounded up,
  /// so at least `reach_radius` at every sample time there).
  widening straight_reach() const { return straight_reach_; }

  /// A rectangle of grid nodes: rows (accelerations) × columns (curvatures) of the two families'
  /// grids stacked (both have the same curvatures), or of their nominal-curvature columns. Its
  /// samples are `order()[begin, end)`; a block of several samples is followed by its first half,
  /// and `second` is the index of its other half (0 for a single sample).
  struct block {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
    std::uint32_t centre = 0;          ///< the sample at its middle node
    std::uint32_t second = 0;
    double acceleration_spread = 0.0;  ///< largest |a − a_centre| over the block [m/s²]
    double curvature_spread = 0.0;     ///< largest |κ − κ_centre| over the block [1/m]
    double top_acceleration = 0.0;     ///< largest a of the block [m/s²]
    double largest_deceleration = 0.0; ///< largest |a| of the block [m/s²]
    double largest_curvature = 0.0;    ///< largest |κ| of the block [1/m]
  };
  const std::vector<block>& blocks() const {
    for (std::uint32_t b = 0; b < blocks_.size(); ++b) block_of(b);
    return blocks_;
  }
  /// `blocks().size()`, without taking any block's extents.
  std::size_t block_count() const { return blocks_.size(); }
  /// Block `index`: `blocks()[index]`, its curvature extents (and, where the rows moved, all its
  /// extents) taken from the grids on first use after a restart at a new speed (most blocks of a
  /// step are never looked at).
  const block& block_of(std::uint32_t index) const {
    if (stale_extents_[index] != stale_none) {
      const block_range& r = ranges_[index];
      if (stale_extents_[index] == stale_all) {
        fill_extents(grids_[r.grid], r, blocks_[index]);
      } else {
        fill_curvature_extents(grids_[r.grid], r, blocks_[index]);
      }
      stale_extents_[index] = stale_none;
    }
    return blocks_[index];
  }
  /// The blocks that hold every sample once: one per grid.
  const std::vector<std::uint32_t>& roots() const { return roots_; }
  /// The samples in tree order: every block is a contiguous range of it.
  const std::vector<std::uint32_t>& order() const { return order_; }
  /// Most any point of the ego footprint can be from the same point of the footprint of the block's
  /// centre sample at time index k, over the block's samples [m]: the mean-value bound
  /// |Δa| · sup|∂(p, Rθ)/∂a| + |Δκ| · sup|∂(p, Rθ)/∂κ| of the pose (p, θ) at t_k, R the footprint's
  /// bounding radius (see the definition for the derivatives; docs/method.md §4.4). The signed
  /// distance of every sample of the block to a fixed obstacle lies within this of the centre's.
  double block_spread(const block& b, std::size_t k) const;
  /// `block_spread` on the straight part as a function of time, valid at every t ≥ T_h [s]: there it
  /// grows linearly, so it is `base` at T_h plus `rate`·(t − T_h), each rounded up. Computed once per
  /// start and block.
  const widening& straight_spread(std::uint32_t b) const {
    if (!straight_spread_known_[b]) {
      straight_spread_[b] = straight_spread_of(block_of(b));
      straight_spread_known_[b] = 1;
    }
    return straight_spread_[b];
  }
  /// Most the velocity of the reference point of a sample of block b can differ from the centre
  /// sample's at time index k [m/s] (the same mean-value bound for the velocity).
  double velocity_spread(const block& b, std::size_t k) const;
  /// Velocity of sample m's reference point at time index k [m/s], world frame.
  vec2 velocity(std::size_t k, std::size_t m) const;
  /// Largest acceleration of the reference point of a sample of block b from time index k on
  /// [m/s²]: |a| + |κ| v² on the arc, 0 on the straight part.
  double largest_acceleration(const block& b, std::size_t k) const;
  /// `largest_acceleration` of sample m.
  double largest_acceleration(std::size_t k, std::size_t m) const;

 private:
  void fill(std::size_t k, std::size_t m) const;
  /// Placement of sample m at time t [s] in the ego's frame: `maneuver_local_placement` bit for bit,
  /// cheaper on the straight part.
  placement local_placement_at(std::size_t m, double t) const;
  /// A placement in the ego's frame moved into the world, as `maneuver_placement` does.
  placement in_world(const placement& local) const {
    return {ego_.pose.position + rotated(local.position, start_rotation_.x, start_rotation_.y),
            rotated(local.direction, start_rotation_.x, start_rotation_.y)};
  }
  /// Where the placement of sample m at time index k is cached: sample by sample, so that the
  /// walks of one sample over the window (exact values, floors) and a block's centre looked at on
  /// consecutive times read neighbouring memory (the rasters' tests of many samples at one time read
  /// `ordered_placements` instead; time by time, this cache cost the busy roundabout about 3 %).
  std::size_t placement_index(std::size_t k, std::size_t m) const { return m * time_count_ + k; }
  /// How a start relates to the previous one: none; the same speed, so the grids' samples and their
  /// speeds are the previous start's (only the nominal-curvature columns' are computed again); or a
  /// new speed, whose grids were sampled again with the same shape.
  /// new_rows: a new speed at which the rows' accelerations moved too (a slow ego's rows follow the
  /// arc length), so the nominal-curvature columns' blocks are built anew.
  enum class start_kind : std::uint8_t { fresh, same_speed, new_speed, new_rows };
  /// What `block_of` must take anew of a block's extents after a restart at a new speed.
  enum stale : std::uint8_t { stale_none = 0, stale_curvatures = 1, stale_all = 2 };
  /// Everything that depends on the speed, the pose, the window or the nominal curvature: the
  /// caches, the speeds and reaches, the nominal-curvature columns' blocks.
  void start(const ego_state& ego, const collision_window& window, start_kind kind);
  /// A grid of samples: `sample(r, c)` is the sample index of a node; `accelerations[r]`,
  /// `curvatures[c]` its values.
  struct grid_view {
    std::vector<std::size_t> row_start;  ///< sample index of each row's first column
    std::vector<double> accelerations;   ///< [row] [m/s²]
    /// [row] [m/s²]: the rows' accelerations were they evenly spaced in a
    /// (`evenly_spaced_acceleration`), which shape the tree of blocks: equal to `accelerations`
    /// where the arc length is affine in a, and independent of the speed where it is not.
    std::vector<double> shape_accelerations;
    std::vector<double> curvatures;      ///< [column] [1/m]
    bool ascending = false;              ///< both lists ascending (non-strictly)
    std::size_t sample(std::size_t r, std::size_t c) const { return row_start[r] + c; }
  };
  /// The grids of the samples: the two families' stacked when they share their curvatures.
  static std::vector<grid_view> grids_of(const maneuver_samples& samples);
  /// True when two lists of grids have the same rows, columns, orders and shape accelerations.
  static bool same_shape(const std::vector<grid_view>& a, const std::vector<grid_view>& b);
  /// The grid rows [r0, r1) × columns [c0, c1) of grid `grid` that a block covers.
  struct block_range {
    std::uint32_t grid, r0, r1, c0, c1;
  };
  /// A block's centre, spreads and largest values from the nodes of its range.
  static void fill_extents(const grid_view& grid, const block_range& range, block& b);
  /// Its curvature extents alone (what changes with the speed where the rows do not move).
  static void fill_curvature_extents(const grid_view& grid, const block_range& range, block& b);
  /// Adds the block of rows [r0, r1) × columns [c0, c1) of `grid` (number `grid_index`) and its
  /// halves; returns its index.
  std::uint32_t add_block(const grid_view& grid, std::size_t grid_index, std::size_t r0, std::size_t r1,
                          std::size_t c0, std::size_t c1);

  /// What the straight part (t > T_h) of sample m needs: `maneuver_local_placement`'s values at T_h.
  struct straight_part {
    vec2 local;       ///< arc end point in the ego frame [m]
    vec2 along;       ///< heading direction there, in the ego frame
    double speed;     ///< at T_h [m/s]
    vec2 direction;   ///< heading direction in the world
    vec2 start;       ///< arc end point in the world [m]
    vec2 velocity;    ///< speed × direction [m/s]
  };

  /// A placement without default member initialisers, so the cache is allocated uninitialised.
  struct stored {
    double px, py, dx, dy;
  };

  ego_state ego_;
  const maneuver_samples& samples_;
  collision_window window_;
  std::size_t sample_count_;
  std::vector<double> times_;
  vec2 start_rotation_;  ///< (cos, sin) of the start heading
  /// `straight_part` of sample m, computed on first use.
  const straight_part& straight(std::size_t m) const {
    if (straight_known_[m] != known) complete_straight(m);
    return straight_[m];
  }
  void complete_straight(std::size_t m) const;
  mutable std::unique_ptr<straight_part[]> straight_;  ///< [m], valid as far as `straight_known_` says
  /// What `straight_` holds of a sample: nothing, its ego-frame values (kept across restarts at the
  /// same speed), or everything.
  enum straight_state : std::uint8_t { unknown, local_only, known };
  mutable std::vector<std::uint8_t> straight_known_;
  std::vector<double> sample_speed_;
  std::vector<double> sample_point_speed_;
  /// The placements in the ego's frame, [placement_index], valid where `local_known_` holds
  /// `local_generation_` (a new stamp per start with other sample times, 1 to 255): kept across
  /// restarts with the same sample times, so the planning steps at one speed compute their
  /// trigonometry once. About a megabyte at the default resolution, allocated uninitialised (only
  /// the pages written are backed by memory).
  mutable std::unique_ptr<stored[]> local_;
  mutable std::vector<std::uint8_t> local_known_;
  std::uint8_t local_generation_ = 0;
  /// The world placements of `ordered_placements`: component j (x, y, c, s) of tree-order position
  /// p at time index k is `ordered_[k][j · sample_count_ + p]`, valid where
  /// `ordered_known_[k · sample_count_ + p]` holds `ordered_generation_` (a new stamp per start:
  /// the pose changes). A time's columns are allocated uninitialised on its first use (21 KB at the
  /// default resolution: from the heap's free memory, where one block for every time would be
  /// mapped and faulted in anew by every plan from scratch).
  mutable std::vector<std::unique_ptr<double[]>> ordered_;
  mutable std::vector<std::uint8_t> ordered_known_;
  std::uint8_t ordered_generation_ = 0;
  std::size_t time_count_ = 0;          ///< `times_.size()`
  /// Samples of one acceleration share their arc lengths s(t): `travel_row_[m]` is sample m's row,
  /// `row_acceleration_` each row's acceleration (the grids' rows first, `grid_travel_rows_` of
  /// them, kept across restarts; then the nominal-curvature columns'), and `travel_[row ·
  /// time_count_ + k]` = `travelled_distance` at t_k ≤ T_h, valid where `travel_known_` holds
  /// `local_generation_`.
  std::vector<std::uint32_t> travel_row_;
  std::vector<double> row_acceleration_;
  std::size_t grid_travel_rows_ = 0;
  mutable std::vector<double> travel_;
  mutable std::vector<std::uint8_t> travel_known_;
  /// s(t_k) of sample m's acceleration [m], t_k ≤ T_h.
  double travel(std::size_t k, std::size_t m) const;
  /// Rows of the samples from `first` on (see `travel_row_`).
  void assign_travel_rows(std::size_t first);
  double largest_speed_ = 0.0;
  double largest_point_speed_ = 0.0;
  std::vector<double> reach_radius_;
  widening straight_reach_;
  double ego_radius_ = 0.0;  ///< bounding radius of the ego footprint [m]
  /// Upper bounds of the arc length at time t ≤ T_h and of the speed at T_h of a sample of acceleration a.
  double arc_length_bound(double a, double t) const;
  double speed_bound(double a) const;
  widening straight_spread_of(const block& b) const;
  mutable std::vector<widening> straight_spread_;       ///< [block]: `straight_spread`, where known
  mutable std::vector<std::uint8_t> straight_spread_known_;
  std::vector<grid_view> grids_;
  std::vector<block_range> ranges_;  ///< [block]
  mutable std::vector<block> blocks_;          ///< curvature extents valid where not `stale_extents_`
  mutable std::vector<std::uint8_t> stale_extents_;  ///< [block]
  std::vector<std::uint32_t> roots_;
  std::vector<std::uint32_t> order_;
  std::size_t grid_blocks_ = 0;  ///< the first blocks, roots and order entries are the grids'
  std::size_t grid_roots_ = 0;
  std::size_t grid_order_ = 0;
};

/// The cap [m] the planner clamps clearances to (`clearance_field`'s `cap`): far pairs are skipped,
/// and it is far above how much the clearance changes between neighbouring samples (≈ 0.4 m), so
/// the interpolated boundary is unaffected in practice.
inline constexpr double planner_clearance_cap = 2.0;

/// The collision sets of one obstacle for every forecast time, computed only as far as the
/// indices need them (spec §5, §6).
///
/// Signs: for every forecast time τ_i the samples that overlap the obstacle at a sample time before
/// the straight part of the window, or at any time of it (`collisions`, [CSS]; see `clearance_set`)
/// are found exactly, equal to a brute-force test of every sample (`collisions_reference`). Values:
/// the clearance of a sample is computed on demand (`exact`) and is then equal, bit for bit, to
/// `clearances_reference` clamped to ±cap; it can be ≤ 0 where no sample time overlaps (a contact
/// between samples before the straight part). Until then an entry of `set` reads −cap for a
/// collision and +cap otherwise. The interpolating indices read values only at the ends of grid
/// edges whose ends differ in sign (and at saddle cells); the planner makes those exact and takes a
/// contact between samples next to a colliding sample as a collision (docs/method.md §4.4).
///
/// How the signs are found cheaply, each step exact:
/// - forecasts agree up to τ, so the times t ≤ τ_i are rastered once and shared by larger τ;
/// - blocks of samples (`ego_sweep::block`) are decided whole: a block whose centre sample's
///   clearance bound exceeds the block's spread is clear at that time, one whose centre overlaps
///   deeper than the spread overlaps everywhere; only the others are halved, for good;
/// - a clear block waits, in the list of that sample time, for the first time at which one of its
///   samples can overlap: from the largest relative speed over the window and, for the reference
///   points' distance, from how fast that distance changes now (an obstacle moving away is not
///   looked at again soon). Every forecast moves no faster than these allow, so a wait found on the
///   shared times holds for the straight part of every forecast time that shares them;
/// - a sample or block known to collide is not looked at again for that τ;
/// - a sample within θ of the obstacle at a sample time is asked for its exact clearance (a contact
///   between sample times) only where no fixed direction separates the two over some pair of sample
///   times (`separated_throughout`, several steps at once where the gap allows);
/// - on the straight part of the window (from `straight_part_start`) each block is tested once, in
///   closed form: its centre's smallest distance over the whole part (`smallest_signed_distance`)
///   against the block's largest spread there, after a cheaper test of the reference points'
///   closest approach.
/// Holds mutable caches (the exact values): one field must not be used by two threads at once.
class clearance_field {
 public:
  /// `wanted[i]` ≠ 0 for the forecast times whose sets are computed; empty: every one. The sets of
  /// the others are left empty (no sampled collision, +cap) and must not be asked for; what is
  /// computed does not depend on which others are wanted, bit for bit.
  clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                  double cap, std::span<const std::uint8_t> wanted = {});

  /// Working memory of the raster, reused from one field to the next (its contents are not
  /// carried over: a field built with one equals a field built without, bit for bit). Saves
  /// every field's allocation and initialisation of a list link per block of the sweep.
  class raster_scratch;
  /// What a field keeps of its collisions: which samples collide, or also when.
  enum class recording : std::uint8_t { collisions, first_overlaps };
  /// The same, rastering in `scratch`, which no other field may use at the same time; with
  /// `recording::first_overlaps` it also keeps when each sample first overlaps (`first_overlap`).
  clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                  double cap, std::span<const std::uint8_t> wanted, raster_scratch& scratch,
                  recording what = recording::collisions);

  std::size_t forecast_count() const { return taus_.size(); }
  /// True when the set of forecast time i was computed (`wanted`).
  bool evaluated(std::size_t i) const { return wanted_.empty() || wanted_[i] != 0; }
  /// Entry [m] of forecast time i: the exact clearance where known, else −cap for a collision and
  /// +cap otherwise.
  const clearance_set& set(std::size_t i) const { return materialized(slot(i)); }
  /// The samples that overlap the obstacle forecast with forecast time i at a sample time before
  /// the straight part or at any time of it, or touch it between sample times before it (their
  /// exact clearance is ≤ 0 and they came within θ at a sample time): `collisions_reference`.
  const sample_mask& collisions(std::size_t i) const { return sampled_[slot(i)]; }
  bool is_exact(std::size_t i, std::size_t m) const {
    const std::vector<std::uint8_t>& e = exact_[slot(i)];
    return inert_ || (!e.empty() && e[m] != 0);
  }
  /// The clearance of sample m with forecast time i, equal to the clamped brute-force one.
  double exact(std::size_t i, std::size_t m);
  /// True when some sample collides with the obstacle forecast with forecast time i (`collisions`).
  bool collides(std::size_t i) const { return !sampled_[slot(i)].none(); }
  /// When sample m first overlaps the obstacle forecast with forecast time i [s] (signed distance −
  /// margin ≤ 0, as `collisions`): the first such sample time before the straight part, else the
  /// first such time of the straight part (`first_contact`, to 1e-9 s), else `no_collision`; equal
  /// to `first_overlaps_reference`. Only for a field built with `recording::first_overlaps`, and a
  /// forecast time whose set it computed (one it evaluated, or any when the obstacle does not turn);
  /// else std::logic_error.
  double first_overlap(std::size_t i, std::size_t m) const;
  /// True when the obstacle stays farther than the cap from every sample at every time under
  /// every forecast time: every clearance is exactly +cap, so the obstacle changes nothing.
  bool inert() const { return inert_; }
  /// True when the obstacle does not turn (ω = 0): every forecast time gives the same forecast,
  /// so one set serves them all.
  bool forecast_independent() const { return independent_; }
  /// Makes every clearance exact (what `clearances` returns).
  void make_all_exact();

  /// How much work the field has done so far (for measurements, docs/performance.md).
  struct work {
    std::size_t bound_checks = 0;          ///< lower bounds looked at (pose distance, separation)
    std::size_t distance_evaluations = 0;  ///< signed distances at sample times
    std::size_t exact_values = 0;          ///< clearances made exact
    std::size_t refinements = 0;           ///< refinements of a sampled minimum run (`refined_minimum`)
    std::size_t translation_minima = 0;    ///< closed-form minima over the straight part (`smallest_signed_distance`)
    /// Placements of the obstacle computed up front: at the forecast times, then, unless it is
    /// found inert from those alone (`far_at_every_time`), at every sample time the forecast times
    /// share and at the start of each straight part.
    std::size_t placements = 0;
  };
  const work& statistics() const { return work_; }

 private:
  clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                  double cap, std::span<const std::uint8_t> wanted, raster_scratch* reused, recording what);
  /// An obstacle's placement: reference point [m] and heading direction (cos, sin).
  using obstacle_at = placement;
  /// Where the set of forecast time i is kept: 0 for all when one set serves every forecast time
  /// (the forecasts do not depend on τ, or the field was found inert before its raster).
  std::size_t slot(std::size_t i) const { return sampled_.size() == 1 ? 0 : i; }
  /// Obstacle placement at time index k under forecast time i.
  obstacle_at obstacle_pose(std::size_t i, std::size_t k) const;
  /// Obstacle placement at time t of an obstacle that does not turn (ω = 0): `forecast_pose` with
  /// the heading's direction found once, bit for bit.
  obstacle_at straight_forecast(double t) const;
  /// A pose as a placement: the heading as its direction.
  static obstacle_at as_placement(const pose& p);
  /// Obstacle placement at a time t > τ_i under forecast time i: `forecast_pose`'s straight part,
  /// in its order of operations.
  obstacle_at straight_after_turn(std::size_t i, double t) const;
  /// Signed distance − margin of sample m and the obstacle under forecast time i at time t [s]:
  /// `clearance_at` bit for bit.
  double clearance_at_time(std::size_t i, std::size_t m, double t) const;
  /// Signed distance [m] of the ego placed at `position` with heading `direction` and the obstacle
  /// placed at `o`: `signed_distance` of the placed footprints bit for bit.
  double distance(vec2 position, vec2 direction, const obstacle_at& o) const;
  /// The signed distance − margin [m] (`exact`), or a lower bound of it that is ≥ `enough`.
  struct lower_bound {
    double value;
    bool exact;
  };
  /// `distance` − margin of the ego at `p` and the obstacle at `o`, bit for bit — or, for two
  /// rectangles whose face separation − margin is already ≥ `enough`, that separation (it changes
  /// no faster than the signed distance), without the corner distances.
  lower_bound distance_or_bound(const ego_sweep::placement& p, const obstacle_at& o, double enough) const;
  /// Bounds [low, high] of the signed distance − `margin` [m] of two rectangles from their face
  /// separation `face`: where they overlap, high is the face separation − margin; where they are
  /// apart and `corners`, both are `corner_distance()` − margin (their corners' distance); else low
  /// is the face separation − margin less the rounding slack and high +∞. The rasters' one test of a
  /// block's centre or a sample (`corners`: where the margin can still make it overlap).
  struct clearance_bounds {
    double low;
    double high;
  };
  template <class Corners>
  clearance_bounds rectangle_bounds(double face, double margin, bool corners, Corners&& corner_distance);
  /// What the raster of a forecast time knows after some sample times: the samples that overlapped
  /// (tree order, `ego_sweep::order`), and the blocks to look at again, each in the list of the
  /// first time index at which one of its samples can overlap (a block whose halves wait on their
  /// own is in no list).
  struct raster_state {
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    /// The samples that overlapped at a sample time (or on the straight part).
    sample_mask hit;
    /// The samples that came within their refinement threshold θ of the obstacle at a sample time
    /// without overlapping it then, and more: those whose lower bound of the clearance (for two
    /// rectangles the face separation less the margin) came within θ. Only these may touch it
    /// between sample times (tree order).
    sample_mask near;
    std::vector<std::uint32_t> near_at;  ///< [position in tree order]: time index at which it was first near (read only where near)
    std::vector<std::uint32_t> head;  ///< [k]: first block waiting for time index k
    std::vector<std::uint32_t> link;  ///< [block]: the next in the same list (read only for blocks in a list)
    std::vector<double> hit_at;  ///< [position in tree order]: time of the first overlap [s] (read only where hit; empty when not recorded)
    /// The obstacle's placements the state is rastered with, at the time indices before `end`: the
    /// CTRV ones shared by every τ (`turning_`) when `shared`, else those of forecast time `slot`.
    /// What a block may be tested at ahead of time (`overlaps_whole_ahead`).
    bool shared = true;
    std::size_t slot = 0;
    std::size_t end = 0;
    /// No sample hit, every list empty, for `samples` samples, `times` time indices and `blocks`
    /// blocks, recording when samples are hit if `record`; keeps the buffers' memory (`link` and
    /// `hit_at` are written before they are read, so not cleared).
    void reset(std::size_t samples, std::size_t times, std::size_t blocks, bool record);
    /// Block `block` waits for time index k (past the last time: it is done).
    void wait(std::size_t k, std::uint32_t block);
    /// Empties the list of time index k and returns its first block.
    std::uint32_t take(std::size_t k);
    /// Moves the blocks waiting for time index k to k + 1.
    void postpone(std::size_t k);
  };
  /// The obstacle placed for the distances: placement, rectangle (when it is one), footprint (general shapes).
  struct placed_obstacle {
    obstacle_at at;
    placed_rectangle rectangle;
    placed_footprint footprint;
  };
  /// First time index after k at which a distance `gap` [m] above zero at t_k, changing now at
  /// `change` [m/s] with a second derivative of at most `curvature` [m/s²], could reach zero.
  std::uint32_t until_second_order(std::size_t k, double gap, double change, double curvature) const;
  /// True when the raster would find the obstacle inert (every distance it tests before and on
  /// each forecast time's straight part at or above the walking cap), shown from its placements at
  /// the forecast times alone: the distance of its reference point from the centre `start` of the
  /// ego's reach, less the reach's radius at the time, the bounding radii and the margin, is ≥
  /// `walk_cap_` at every sample time and on every straight part (the closed form of the growing
  /// disc). On the curve the forecast times share, the distance at t between two known placements
  /// at τ_l ≤ t ≤ τ_{l+1} is bounded below by max(d_l − v (t − τ_l), d_{l+1} − v (τ_{l+1} − t)) (the
  /// reference point moves at speed v); after τ_i it is taken exactly. Only where it holds is it
  /// used, so a field is inert whether or not this shows it (docs/performance.md, How the fast
  /// path works).
  bool far_at_every_time(vec2 start) const;
  /// How far the obstacle's reference point, `distance` [m] from the centre of the ego's reach at
  /// time index k, lies outside that reach: less its radius then, the bounding radii and the margin
  /// [m]. At or above the walking cap no sample comes within it; above θ (`band_`) none can overlap.
  double reach_gap(std::size_t k, double distance) const;
  /// The least `reach_gap` over the straight part of forecast time i (slot i), the obstacle starting
  /// at `offset` [m] from the reach's centre and moving at `velocity` [m/s] (the closest approach to
  /// the growing disc, rounded down).
  double straight_reach_gap(std::size_t i, vec2 offset, vec2 velocity) const;
  /// Marks in `state` every sample that overlaps the obstacle placed at `o` at time index k.
  void raster(std::size_t k, const obstacle_at& o, raster_state& state);
  /// `raster` of block `index` (and its halves when it is undecided as a whole).
  void raster_block(std::uint32_t index, std::size_t k, const placed_obstacle& o, raster_state& state);
  /// True when every sample of block b overlaps the obstacle at one of the next `lookahead_steps`
  /// time indices after k that `state` is rastered with (before its `end`): the centre's clearance
  /// is below minus the block's spread there. A block that a time index leaves undecided is often
  /// inside the obstacle a step later (it moves up to a metre a step), where one test decides it.
  bool overlaps_whole_ahead(const ego_sweep::block& b, std::size_t k, const raster_state& state);
  /// `raster` of the samples of block `index` one by one, several at once (two rectangles): each
  /// sample's test is the single sample's of `raster_block`; the block waits for the first time one
  /// of them can overlap.
  void raster_samples(std::uint32_t index, std::size_t k, const placed_obstacle& o, raster_state& state);
  /// Blocks of at most this many samples that a time leaves undecided have their samples tested
  /// together (`raster_samples`) instead of being halved down to single samples: 8, 16 and 32 took
  /// the one-obstacle benchmark step the same time within the noise (docs/performance-history.md, seventeenth round).
  static constexpr std::size_t together = 16;
  /// Time indices a block undecided at one sample time is tried at ahead (`overlaps_whole_ahead`):
  /// 2 took the fewest instructions on the one-obstacle benchmark step among 1, 2 and 3 (7.63, 7.61
  /// and 7.65 M, before the samples of small blocks were tested together).
  static constexpr std::size_t lookahead_steps = 2;
  /// A block of at most this many samples that the straight part's test leaves undecided has its
  /// samples tested one by one instead of being halved (`straight_part_block`). On the saved dense
  /// roundabout input 16 took the plan from 50.36 M to 47.68 M instructions (4: 49.09 M, 24: 47.59 M,
  /// 64: 47.96 M, every sample of the grid: 59.14 M), and the one-obstacle input from 8.62 M to 8.58 M.
  static constexpr std::size_t straight_together = 16;
  /// Marks in `state` every sample not marked yet that overlaps the obstacle forecast with forecast
  /// time i at some time of the straight part (the closed form, block by block from the roots).
  void raster_straight_part(std::size_t i, raster_state& state);
  /// `raster_straight_part` of block `index` (and its halves when it is undecided as a whole).
  void straight_part_block(std::uint32_t index, std::size_t i, raster_state& state);
  /// The relative motion of sample m and the obstacle on the straight part of forecast time i:
  /// both placed at its start, and the translation of the ego relative to the obstacle to T_c.
  struct straight_motion {
    placement ego;
    obstacle_at obstacle;
    translation motion;
  };
  straight_motion straight_motion_of(std::size_t i, std::size_t m) const;
  /// The smallest signed distance − margin of sample m over the straight part of forecast time i
  /// [m], and when it is reached (after the part's start) [s]: `smallest_signed_distance`.
  translation_minimum straight_minimum(const straight_motion& part);
  /// True when sample m collides with the obstacle on the straight part: `straight_minimum` ≤ 0,
  /// decided as `collisions_reference` decides it (`signed_distance_reaches` for rectangles and discs).
  bool straight_collides(const straight_motion& part);
  /// True when `straight_minimum` can be ≤ `level` [m] (exact up to rounding at the level itself):
  /// `signed_distance_reaches` at `level` + margin for rectangles and discs.
  bool straight_within(const straight_motion& part, double level);
  /// For rectangles and discs: the centre's face separations over the straight part
  /// (`face_separations`), for the block tests.
  face_separations straight_separations(const straight_motion& part);
  /// True when the reference points stay farther apart than `gap` plus the bounding radii and the
  /// margin over the whole straight part [m] (their closest approach, rounded so as to be sure): then
  /// `straight_minimum` ≥ `gap`.
  bool straight_apart(const straight_motion& part, double gap) const;
  /// Time [s] of the first overlap of sample m on the straight part, from the part's start
  /// (`first_contact` at level margin), or +∞.
  double straight_first_contact(const straight_motion& part) const;
  /// Rates of sample m: of its reference point's distance and of the signed distance [m/s].
  double centre_rate(std::size_t m) const { return sweep_.sample_speed(m) + obstacle_.motion.speed; }
  double distance_rate(std::size_t m) const { return sweep_.sample_point_speed(m) + obstacle_turn_speed_; }
  /// θ of sample m (`refinement_threshold`) [m].
  double sample_threshold(std::size_t m) const {
    return refinement_threshold(distance_rate(m), sweep_.window().time_step);
  }
  /// False when sample m, first near the obstacle forecast with forecast time i at time index
  /// `first_near` (`raster_state::near`: every earlier sample time is farther than θ), provably does not touch
  /// it between two neighbouring sample times before the straight part, so that `exact` is > 0:
  /// every pair of sample times from `first_near` − 1 to the first at or after t_s is
  /// `separated_throughout` (several at once where the gap allows), but where both ends of a pair are
  /// farther than θ = L·step/2 (a contact at t between t_k and t_{k+1} would leave one of them within
  /// L·step/2 of it). For rectangles, and a rectangle and a disc; true for other shapes. The pairs
  /// within the times t ≤ τ_i are the same for every larger τ: each sample walks them once
  /// (`shared_proof`), and each forecast time walks only its own pairs after them.
  bool may_touch_between(std::size_t i, std::size_t m, std::size_t first_near);
  /// `refined_minimum` of sample m under forecast time i around time index k, where the clearance
  /// is `at_sample`; searched once per sample when the bracket lies in the times shared by every τ.
  double refined_at(std::size_t i, std::size_t m, std::size_t k, double at_sample);

  /// The exact walk of one sample over the shared times t ≤ τ (the same for every larger τ).
  struct prefix_walk {
    running_minimum minimum;
    std::size_t next = 0;   ///< next time index to look at
    std::size_t until = 0;  ///< time indices [0, until) are done
  };

  const ego_sweep& sweep_;
  forecast_obstacle obstacle_;
  std::vector<double> taus_;
  std::vector<std::uint8_t> wanted_;  ///< [i]: the set of forecast time i is computed (empty: every one)
  double cap_;
  double walk_cap_;
  std::size_t horizon_index_ = 0;  ///< first sample time index at or after T_h
  double reach_;          ///< bounding radii of ego and obstacle, and the rounding slack [m]
  double centre_rate_;    ///< Lipschitz constant of the reference points' distance [m/s]
  double distance_rate_;  ///< L: Lipschitz constant of the signed distance [m/s]
  double centre_steps_;    ///< 1 / (centre_rate_ · time step) [1/m]: sample steps a gap of 1 m needs to close
  double distance_steps_;  ///< 1 / (distance_rate_ · time step) [1/m]
  /// θ of the fastest sample, refinement_threshold(L, step) [m]: no sample that stays farther than
  /// this at two neighbouring sample times can touch the obstacle between them.
  double band_ = 0.0;
  bool inert_ = false;
  bool independent_ = false;
  std::vector<obstacle_at> turning_;         ///< [k]: CTRV placement at t_k, shared by every τ ≥ t_k (every τ when ω = 0)
  std::vector<obstacle_at> turn_end_;        ///< [i]: placement at τ_i, where the straight part starts
  std::vector<std::size_t> first_straight_;  ///< [i]: first k with t_k > τ_i (none when ω = 0)
  std::vector<double> part_start_;           ///< [slot]: t_s, start of the straight part of the window (`straight_part_start`) [s]
  std::vector<std::size_t> part_first_;      ///< [slot]: first k with t_k ≥ t_s: the sample times before it are sampled
  std::vector<obstacle_at> part_obstacle_;   ///< [slot]: obstacle placement at t_s
  std::vector<vec2> part_velocity_;          ///< [slot]: obstacle velocity on the straight part [m/s]
  /// End of the times shared by every forecast time from i on: min(first_straight_, part_first_).
  std::size_t shared_end(std::size_t i) const { return std::min(first_straight_[i], part_first_[slot(i)]); }
  vec2 heading_direction_;      ///< (cos, sin) of the obstacle's heading now
  double obstacle_turn_speed_;  ///< largest speed of an obstacle point [m/s]: v + |ω| R
  double obstacle_acceleration_ = 0.0;  ///< of the obstacle's reference point while it turns [m/s²]: v |ω|
  /// Which closed form the distances use: two rectangles, a rectangular ego and a disc, or the
  /// general placed footprints.
  enum class shape_pair : std::uint8_t { rectangles, rectangle_disc, general };
  shape_pair shapes_ = shape_pair::general;
  vec2 ego_half_;               ///< half length and half width of the ego rectangle [m]
  vec2 obstacle_half_;          ///< of the obstacle rectangle [m]
  double obstacle_radius_ = 0.0;  ///< of the obstacle disc [m]
  work work_;
  /// Slot i's entries as `set` describes them, made on the first exact value or `set` call of the
  /// slot (most slots of a step are never read by value: their vectors are never allocated).
  clearance_set& materialized(std::size_t i) const;
  mutable std::vector<clearance_set> sets_;  ///< [slot][m] (empty until `materialized`)
  std::vector<sample_mask> sampled_;  ///< [slot]: the sampled collisions
  std::vector<std::vector<double>> first_overlap_;  ///< [slot][m]: `first_overlap` (only when recorded, for the slots computed)
  std::vector<std::vector<std::uint32_t>> argmin_;  ///< [slot][m]: time index of the sampled minimum of an exact value (allocated on first use)
  std::vector<std::vector<std::uint8_t>> exact_;  ///< [slot][m]: the entry of `sets_` is exact (allocated on the slot's first exact value; every entry is exact when inert)
  /// "No entry" in the index tables below and in `argmin_`.
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  /// How far `may_touch_between` has proven sample m apart over the shared times (t ≤ τ, every
  /// larger τ the same), from the pair before its first time within θ.
  struct shared_proof {
    std::uint32_t first_near = none;  ///< the walk's `first_near`; `none`: not walked yet
    std::uint32_t next = 0;           ///< every pair of sample times from first_near − 1 to `next` is proven apart
    std::uint32_t limit = 0;          ///< the last time index the walk was allowed to end a pair at
    std::uint8_t stride = 1;          ///< the walk's state at `next`
    std::uint8_t direction = 4;
    bool failed = false;  ///< a pair of neighbouring shared times is not proven apart (every later call: true)
  };
  std::vector<shared_proof> shared_proofs_;  ///< [m] (allocated on first use)
  std::vector<prefix_walk> prefix_;          ///< the walks of the samples walked so far
  std::vector<std::uint32_t> prefix_of_;     ///< [m]: sample m's walk in `prefix_`, or `none` (allocated on first use)
  /// Sample m's walk over the shared times, or null when it has none yet.
  const prefix_walk* walked_prefix(std::size_t m) const {
    return prefix_of_.empty() || prefix_of_[m] == none ? nullptr : &prefix_[prefix_of_[m]];
  }
  /// A refined minimum on shared times: (time index, value), and the sample's previous one.
  struct refined_entry {
    std::size_t argmin;
    double value;
    std::uint32_t next;
  };
  std::vector<refined_entry> refined_;       ///< every sample's refined minima, as lists
  std::vector<std::uint32_t> refined_head_;  ///< [m]: sample m's last refined minimum, or `none` (allocated on first use)
};

class clearance_field::raster_scratch {
  friend class clearance_field;
  raster_state shared_;
  raster_state own_;
};

/// Start t_s [s] of the straight part of the window under forecast time τ [s], from which the ego
/// (after T_h) and the obstacle (after τ) both go straight at constant velocities: T_h when the
/// obstacle does not turn (ω = 0: every forecast is straight), else max(T_h, τ); at most T_c.
double straight_part_start(const forecast_obstacle& obstacle, double forecast_time, const collision_window& window);

/// The collision sets of one obstacle for every forecast time, by brute force (the reference for
/// `clearance_field::collisions`): mask i holds the samples whose signed distance − margin under
/// `forecast_times[i]` is ≤ 0 at some sample time before `straight_part_start`, or whose
/// `smallest_signed_distance` − margin over the straight part is ≤ 0, or — a contact between
/// sample times — whose smallest signed distance − margin at those sample times is at most their θ
/// (`refinement_threshold` of the sample's and the obstacle's largest point speeds) and whose
/// `refined_minimum` around it is ≤ 0.
std::vector<sample_mask> collisions_reference(const ego_state& ego, const maneuver_samples& samples,
                                              const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                                              const collision_window& window);

/// The reference for `clearance_field::first_overlap`, by brute force: entry [m] is the first sample
/// time before the straight part at which sample m's signed distance − margin to the obstacle
/// forecast with `forecast_time` is ≤ 0, else its first such time on the straight part
/// (`first_contact`), else, for a contact between sample times (`collisions_reference`), the
/// sample time of the sampled minimum, else `no_collision` [s].
std::vector<double> first_overlaps_reference(const ego_state& ego, const maneuver_samples& samples,
                                             const forecast_obstacle& obstacle, double forecast_time,
                                             const collision_window& window);

/// Clearances of one obstacle for every forecast time (spec §5): entry [i][m] is the signed
/// clearance (`clearance_set`) of sample m with the obstacle forecast with `forecast_times[i]`
/// (ascending), clamped to [−cap, cap]. A `clearance_field` made exact everywhere: equal, bit for
/// bit, to `clearances_reference` clamped to ±cap.
std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap);

/// The reference for `clearances`: every sample, forecast time and sample time before the straight
/// part, no pruning, no cap; the same `refined_minimum` and `smallest_signed_distance`.
std::vector<clearance_set> clearances_reference(const ego_state& ego, const maneuver_samples& samples,
                                                const forecast_obstacle& obstacle,
                                                std::span<const double> forecast_times,
                                                const collision_window& window);

/// Collision sets [CSS](τ_i) of the reference planner (spec §11), in continuous time: mask i holds
/// the samples that `verified_collision_free` cannot prove free of the obstacle forecast with
/// `forecast_times[i]` at any time in [0, T_c] — they overlap, or pass within (largest relative
/// point speed × `proof_resolution`) of it.
std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window, double proof_resolution);

}  // namespace mm
