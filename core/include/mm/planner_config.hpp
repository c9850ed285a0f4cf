#pragma once

#include <cstddef>
#include <vector>

#include "mm/assignment_search.hpp"
#include "mm/displacement_set.hpp"
#include "mm/forecast_policy.hpp"
#include "mm/maneuver_choice.hpp"

namespace mm {

/// Everything the planner can be told, with the defaults of the spec.
struct planner_config {
  double displacement_horizon = 1.0;  ///< T_h [Δt^h, s] (spec §3)
  double collision_window = 3.0;      ///< T_c [s] ≥ T_h and ≥ the largest forecast time (spec §5)
  double forecast_step = 0.125;       ///< Δτ [s] (spec §4)
  std::size_t forecast_count = 17;    ///< τ_i = i·Δτ, i = 0..forecast_count−1 (spec §4)
  double history_window = 0.5;        ///< H [s]: observations used to estimate v_j, ω_j (spec §4)
  double safety_margin = 0.0;         ///< inflation of every obstacle [m] (spec §2)
  forecast_policy policy;             ///< ADJ, constant τ (spec §7), or robust (docs/method.md §8)
  effort_weights effort;              ///< w_lon, w_lat of J (spec §8)
  bool urgent_steering = false;       ///< spec §8.3, the paper's case-study setting
  /// Samples per family: 14 accelerations × 19 curvatures, the cheapest grid measured to meet
  /// spec §11's 0.02 bound against the reference on every step of the built-in scenarios
  /// (docs/method.md §7, "Which grid is the cheapest on the built-in scenarios").
  sampling_resolution resolution;
  /// Upper bound on the collision time step [s]; the step is also kept below the tunneling bound
  /// of spec §5 for every relevant obstacle.
  double max_time_step = 0.05;
  assignment_search_kind assignment_search = assignment_search_kind::coordinate_ascent;  ///< spec §9
  std::size_t max_exhaustive_assignments = 1'000'000;  ///< refuse an exhaustive search larger than this
  bool record_samples = false;  ///< fill `plan_result::samples` (for drawing the sets)
  /// Compute the column of the Maneuverability Map (`plan_result::mi_brake`, `mi_accelerate`: every
  /// forecast time, spec §6). When false, only the forecast times the decision reads are evaluated —
  /// the constant policy's (capped at TTC), or under ADJ those not excluded (with several obstacles,
  /// each obstacle's τ_i ≤ TTC_j) — and the two vectors are left empty; everything else (command,
  /// mode, τ̄, family, the selected indices, TTC, `excluded`) is the same, bit for bit. For runs whose
  /// maps nobody reads, such as the runs of a sweep. `record_samples` computes the column anyway.
  bool map_column = true;
  /// Compute only what the command needs (docs/method.md §4.6): a step whose nominal maneuver is
  /// proven collision-free with each relevant obstacle alone under each of its forecast times
  /// τ_i ≤ TTC_j (the speed-bound proof of `verified_collision_free`), and on the drivable area,
  /// returns u_nom without computing any Maneuverability Index: spec §8 rule 1 applies it under
  /// whatever forecast times the indices would select. The command, mode, TTC and `excluded` are
  /// those of the full step, bit for bit; `plan_result::indices_computed` is then false, and τ̄,
  /// the family, the selected indices and each obstacle's forecast index are left at their
  /// defaults. Applies only without the map column (`map_column` and `record_samples` false) and
  /// with the coordinate-ascent search. For runs that keep only the commands, such as a sweep's
  /// (the simulator sets it from `mm::sim::run_options::decision_only`, whatever a vehicle's says).
  bool decision_only = false;

  friend bool operator==(const planner_config&, const planner_config&) = default;
};

/// The forecast grid τ_i = i·Δτ [s] (spec §4).
std::vector<double> forecast_times(const planner_config& config);

/// The most forecast times the planner takes (`planner_config::forecast_count`; 17 in the paper).
inline constexpr std::size_t largest_forecast_count = 1000;

/// The largest side of the sampling grid the planner takes (`planner_config::resolution`, either
/// field).
inline constexpr std::size_t largest_sampling_side = 2001;

/// The most (sampled maneuver, collision sample time) pairs one planning step may hold: 2 families
/// × accelerations × curvatures maneuvers, times `sample_time_count` sample times. The finest
/// resolution (2001 × 2001) over the default window (3 s at 0.05 s, 61 sample times) fits: about
/// 7.6 GB and a minute. A larger step is refused as invalid instead of running out of memory or
/// time (docs/method.md, deviations).
inline constexpr double largest_sample_time_pairs = 5e8;

/// Sample times of a collision window of `duration` [s] at time steps of at most `step` [s]:
/// ⌈duration/step⌉ + 1 (both ends), as a double (it may exceed every integer type).
double sample_time_count(double duration, double step);

/// Sampled maneuvers of both families at `resolution`, as a double.
double sampled_maneuver_count(const sampling_resolution& resolution);

}  // namespace mm
