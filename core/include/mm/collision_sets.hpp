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

namespace mm {

/// Signed distance − margin [m] between the ego executing `u` and the obstacle forecast with
/// forecast time `tau`, at time t.
double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window);

/// Signed clearance of every sample: the smallest signed distance − margin [m] between the ego
/// executing the sample and an obstacle over the collision window. Negative ⇔ the sample collides
/// [CSS]; the magnitude lets estimators place the boundary between samples. Clamped to ±cap.
///
/// Precisely, with d_k the signed distance − margin at the sample times t_k (`sample_times`) and
/// θ = `refinement_threshold` of the pair (how far d can fall between a sample time and the
/// nearest other time):
/// - if min_k d_k ≤ 0 or min_k d_k > θ: min(min_k d_k, `refined_minimum` around the argmin);
/// - otherwise (it passes within θ without touching at a sample time): min(min_k d_k, the
///   `refined_minimum` around every local minimum d_j ≤ θ of the sampled sequence) — d_j ≤ d_{j±1}
///   where those exist. Every dip that could reach 0 between samples is refined, so the sign is
///   that of the continuous-time minimum; and a walk that looks at every time at which d can be ≤ θ
///   sees every such dip, in any order.
using clearance_set = std::vector<double>;

/// Largest speed [m/s] of the ego's reference point executing `u` over the window: v_max, the larger
/// of the start speed and the speed at T_h (the speed is monotonic in t, then constant).
double largest_speed(const ego_state& ego, const maneuver& u, double horizon);

/// Largest speed [m/s] of any point of the ego footprint executing `u` over the window:
/// v_max (1 + |κ| R).
double largest_point_speed(const ego_state& ego, const maneuver& u, double horizon);

/// Largest speed [m/s] of any point of the obstacle's footprint under any forecast: v + |ω| R.
double largest_point_speed(const forecast_obstacle& obstacle);

/// Most the signed distance of a pair whose points move at most at `rate` [m/s] (the sum of both
/// footprints' largest point speeds) can fall between a time and the nearest sample time [m]:
/// rate · step / 2, rounded up. A sampled minimum above it refines to a positive clearance.
double refinement_threshold(double rate, double time_step);

/// The ego's trajectories for every sample of a `maneuver_samples` over the collision window,
/// shared by all obstacles and forecast times of a planning step. Placements are computed lazily,
/// the first time a (sample, sample time) pair is asked for, and kept; on the straight part
/// (t > T_h) they cost no trigonometry. Every placement equals `maneuver_placement` bit for bit.
///
/// Holds mutable caches: one sweep must not be used by two threads at once.
class ego_sweep {
 public:
  ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window);

  const ego_state& ego() const { return ego_; }
  const maneuver_samples& samples() const { return samples_; }
  const collision_window& window() const { return window_; }
  std::size_t sample_count() const { return sample_count_; }
  const std::vector<double>& times() const { return times_; }

  /// Position [m] and heading direction (cos θ, sin θ) of a sample.
  using placement = mm::placement;
  /// Placement of sample m at time index k.
  placement at(std::size_t k, std::size_t m) const {
    const std::size_t index = k * sample_count_ + m;
    if (!known_[index]) fill(k, m);
    const stored& p = placements_[index];
    return {{p.px, p.py}, {p.dx, p.dy}};
  }
  /// Placement of sample m at any time t [s]: `maneuver_placement` bit for bit, cheaper on the
  /// straight part.
  placement placement_at(std::size_t m, double t) const;
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

 private:
  void fill(std::size_t k, std::size_t m) const;

  /// What the straight part (t > T_h) of sample m needs: `maneuver_local_placement`'s values at T_h.
  struct straight_part {
    vec2 local;       ///< arc end point in the ego frame [m]
    vec2 along;       ///< heading direction there, in the ego frame
    double speed;     ///< at T_h [m/s]
    vec2 direction;   ///< heading direction in the world
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
  std::vector<straight_part> straight_;
  std::vector<double> sample_speed_;
  std::vector<double> sample_point_speed_;
  mutable std::vector<std::uint8_t> known_;
  mutable std::unique_ptr<stored[]> placements_;
  double largest_speed_ = 0.0;
  double largest_point_speed_ = 0.0;
  std::vector<double> reach_radius_;
};

/// The collision sets of one obstacle for every forecast time, computed only as far as the
/// indices need them (spec §5, §6). For every forecast time τ_i and sample m the *sign* of the
/// clearance is always right; its *value* is computed on demand (`exact`) and is then equal, bit
/// for bit, to `clearances_reference` clamped to ±cap. Until then a positive clearance reads
/// +cap and a negative one −cap. The interpolating indices (`maneuverability_index`) use values
/// only at the ends of grid edges whose ends differ in sign (and at saddle cells), so a caller
/// makes those exact first.
///
/// How the signs are found cheaply, each step exact:
/// - forecasts agree up to τ, so the walk over t ≤ τ_i is done once and shared by larger τ;
/// - a sample is skipped at a time when a lower bound — the distance of bounding discs, or the last
///   clearance computed minus the largest relative point speed L times the time elapsed — shows it
///   stays above the threshold that matters: L·step/2 (above it, the refined minimum cannot reach
///   0), then 0 once it has come that close;
/// - before the per-τ walks, one pass against a disc holding the obstacle under every τ_i tells
///   each sample the first time it can come within its threshold under any of them;
/// - a sample that comes within L·step/2 of contact without touching at a sample time is refined
///   (`exact`), because only the refined minimum decides its sign.
/// Holds mutable caches (the exact values): one field must not be used by two threads at once.
class clearance_field {
 public:
  clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                  double cap);

  std::size_t forecast_count() const { return taus_.size(); }
  /// Entry [m] of forecast time i: the exact clearance where known, else ±cap with the right sign.
  const clearance_set& set(std::size_t i) const { return sets_[slot(i)]; }
  bool is_exact(std::size_t i, std::size_t m) const { return exact_[slot(i)][m] != 0; }
  /// The clearance of sample m with forecast time i, equal to the clamped brute-force one.
  double exact(std::size_t i, std::size_t m);
  /// `exact(i, m)` when that can be below `ceiling` [m]; otherwise a value ≥ `ceiling` (then
  /// `exact(i, m)` ≥ `ceiling` too), found by a walk that stops looking at a sample time once it
  /// is provably ≥ ceiling + L·step/2. What a minimum over obstacles needs from an obstacle that
  /// cannot lower it.
  double exact_below(std::size_t i, std::size_t m, double ceiling);
  /// True when no entry of forecast time i's set is below the cap: the obstacle cannot lower a
  /// minimum over obstacles that starts from the cap.
  bool all_at_cap(std::size_t i) const { return below_cap_[slot(i)] == 0; }
  /// True when some sample collides with the obstacle forecast with forecast time i [CSS ≠ ∅].
  bool collides(std::size_t i) const { return colliding_[slot(i)] != 0; }
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
  };
  const work& statistics() const { return work_; }

 private:
  /// An obstacle's placement: reference point [m] and heading direction (cos, sin).
  using obstacle_at = placement;
  /// Where the set of forecast time i is kept: 0 for all when the forecasts do not depend on τ.
  std::size_t slot(std::size_t i) const { return independent_ ? 0 : i; }
  /// Obstacle placement at time index k under forecast time i.
  obstacle_at obstacle_pose(std::size_t i, std::size_t k) const;
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
  /// Rates of sample m: of its reference point's distance and of the signed distance [m/s].
  double centre_rate(std::size_t m) const { return sweep_.sample_speed(m) + obstacle_.motion.speed; }
  double distance_rate(std::size_t m) const { return sweep_.sample_point_speed(m) + obstacle_turn_speed_; }
  /// θ of sample m (`refinement_threshold`) [m].
  double sample_threshold(std::size_t m) const {
    return refinement_threshold(distance_rate(m), sweep_.window().time_step);
  }
  /// `refined_minimum` of sample m under forecast time i around time index k, where the clearance
  /// is `at_sample`; searched once per sample when the bracket lies in the times shared by every τ.
  double refined_at(std::size_t i, std::size_t m, std::size_t k, double at_sample);

  /// The local minima ≤ θ of one sample's sampled clearance, met in time order by a walk that
  /// looks at every time at which the clearance can be ≤ θ (a time it skips is > θ).
  struct dips {
    std::size_t candidate = no_index;  ///< last time looked at if ≤ θ and ≤ the time before it
    double candidate_value = 0.0;
    std::size_t last = no_index;       ///< last time looked at
    double last_value = 0.0;
    double refined = std::numeric_limits<double>::infinity();  ///< smallest refinement of a confirmed dip
    static constexpr std::size_t no_index = std::numeric_limits<std::size_t>::max();
  };
  /// A local minimum of the sampled clearance: its time index (`dips::no_index`: none) and value [m].
  struct dip {
    std::size_t at = dips::no_index;
    double value = 0.0;
  };
  /// Where a sample stands in the walk that decides its sign, and the samples a walk follows
  /// (defined with the walk).
  struct sign_state;
  struct sign_walk;

  /// Tells `d` the walk is at time index k (`value` looked at there, or skipped: > θ). Returns the
  /// local minimum this confirms, if any.
  static dip visit(dips& d, std::size_t k, bool looked, double value, double theta);
  /// The walk is over: the candidate still waiting for the time after it is a local minimum.
  static dip finish(dips& d);

  /// The exact walk of one sample over the shared times t ≤ τ (the same for every larger τ).
  struct prefix_walk {
    running_minimum minimum;
    dips low;
    std::size_t next = 0;   ///< next time index to look at
    std::size_t until = 0;  ///< time indices [0, until) are done
  };

  const ego_sweep& sweep_;
  forecast_obstacle obstacle_;
  std::vector<double> taus_;
  double cap_;
  double walk_cap_;
  double reach_;          ///< bounding radii of ego and obstacle, and the rounding slack [m]
  double centre_rate_;    ///< Lipschitz constant of the reference points' distance [m/s]
  double distance_rate_;  ///< L: Lipschitz constant of the signed distance [m/s]
  bool inert_ = false;
  bool independent_ = false;
  std::vector<obstacle_at> turning_;         ///< [k]: CTRV placement at t_k, shared by every τ ≥ t_k (every τ when ω = 0)
  std::vector<obstacle_at> turn_end_;        ///< [i]: placement at τ_i, where the straight part starts
  std::vector<std::size_t> first_straight_;  ///< [i]: first k with t_k > τ_i (none when ω = 0)
  double obstacle_turn_speed_;  ///< largest speed of an obstacle point [m/s]: v + |ω| R
  /// Which closed form the distances use: two rectangles, a rectangular ego and a disc, or the
  /// general placed footprints.
  enum class shape_pair : std::uint8_t { rectangles, rectangle_disc, general };
  shape_pair shapes_ = shape_pair::general;
  vec2 ego_half_;               ///< half length and half width of the ego rectangle [m]
  vec2 obstacle_half_;          ///< of the obstacle rectangle [m]
  double obstacle_radius_ = 0.0;  ///< of the obstacle disc [m]
  work work_;
  std::vector<clearance_set> sets_;
  std::vector<std::size_t> below_cap_;  ///< [slot]: entries of the set below the cap
  std::vector<std::size_t> colliding_;  ///< [slot]: samples that collide (negative entries)
  std::vector<std::vector<double>> floor_;  ///< [slot][m]: shown by `exact_below` to be ≤ the clearance (allocated on first use)
  std::vector<std::vector<std::uint8_t>> exact_;
  std::vector<prefix_walk> prefix_;                                    ///< [m]
  std::vector<std::vector<std::pair<std::size_t, double>>> refined_;  ///< [m]: (time index, refined minimum) on shared times
};

/// Clearances of one obstacle for every forecast time (spec §5): entry [i][m] is the signed
/// clearance of sample m with the obstacle forecast with `forecast_times[i]` (ascending): the
/// `refined_minimum` of the signed distance − margin over the sample times of the sweep, clamped
/// to [−cap, cap]. A `clearance_field` made exact everywhere: equal, bit for bit, to
/// `clearances_reference` clamped to ±cap.
std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap);

/// The reference for `clearances`: every sample, forecast time and sample time, no pruning, no cap;
/// the same `refined_minimum`.
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
