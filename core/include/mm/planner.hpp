#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mm/drivable_area.hpp"
#include "mm/forecast.hpp"
#include "mm/input_bounds.hpp"
#include "mm/maneuver.hpp"
#include "mm/maneuver_choice.hpp"
#include "mm/planner_config.hpp"

namespace mm {

/// One planning step: the ego, what it wants to do, what it has observed.
struct plan_input {
  double time = 0.0;                      ///< planning time [s]; no observation may be later
  ego_state ego;
  maneuver nominal;                       ///< u_nom: path following and speed keeping (spec §8); clamped to the limits
  std::vector<obstacle_track> obstacles;
  planner_config config;
  /// The optional road constraint (spec §5): when set and the ego starts on it, a maneuver whose
  /// footprint leaves this area within T_h is unsafe in both families (`road_constraint.hpp`).
  /// Shared, as one area serves every vehicle and step of a scenario.
  std::shared_ptr<const mm::drivable_area> drivable_area;
};

enum class plan_status : std::uint8_t { ok, invalid_input };

/// How the planner sees one obstacle.
struct obstacle_assessment {
  std::uint32_t id = 0;
  bool relevant = false;           ///< false: too far to reach within T_c, so it cost nothing (spec §9)
  motion_estimate motion;
  double time_to_collision = 0.0;  ///< TTC with this obstacle [s], ∞ for none (spec §6)
  std::size_t forecast_index = 0;  ///< the forecast time this obstacle was given (spec §9)
};

/// The sampled maneuvers of one step and their safety, to draw or check the sets (spec §3, §5).
struct sample_snapshot {
  std::vector<maneuver> maneuvers;
  std::vector<family> families;
  std::vector<vec2> end_points;                     ///< displacements, world frame [m]
  std::vector<double> area_weights;                 ///< [m²]; 0 on the nominal-curvature columns
  std::vector<std::uint8_t> on_nominal_curvature;   ///< 1 on the nominal-curvature columns
  std::vector<std::vector<std::uint8_t>> safe_by_forecast;  ///< [i][m]: safe with every obstacle at τ_i
  std::vector<std::uint8_t> safe_selected;          ///< [m]: safe under the selected forecast times
};

/// Everything one planning step computes (spec §6–§9).
/// How much collision work a planning step did (for cost measurements, docs/performance.md);
/// zero on the reference path. Deterministic: a function of the input alone.
struct plan_work {
  std::size_t relevant_obstacles = 0;    ///< obstacles that can interact within T_c (spec §9)
  std::size_t bound_checks = 0;          ///< (sample, time) pairs looked at through a lower bound
  std::size_t distance_evaluations = 0;  ///< signed distances at sample times
  std::size_t refinements = 0;           ///< refinements of a sampled clearance minimum (`refined_minimum`)
  std::size_t translation_minima = 0;    ///< closed-form minima over the straight part of the window (`smallest_signed_distance`)
  std::size_t assignments_evaluated = 0; ///< forecast-time assignments whose room or rough room was computed (spec §9)
};

struct plan_result {
  plan_status status = plan_status::ok;
  std::string error;                       ///< what was wrong with the input, when not ok

  maneuver command;                        ///< the chosen u: finite and within the limits
  planning_mode mode = planning_mode::nominal;
  family selected_family = family::brake;  ///< family chosen by the MI comparison at τ̄ (spec §7)
  double forecast_time = 0.0;              ///< τ̄ [s]: of the most urgent obstacle when there are several
  std::size_t forecast_index = 0;          ///< ī
  double mi_brake_selected = 1.0;          ///< MI− under the selected forecast times
  double mi_accelerate_selected = 1.0;     ///< MI+ under the selected forecast times
  /// Robust policy only: true when the command came from the robust sets, the maneuvers safe under
  /// every non-excluded forecast time of every obstacle; the selected indices are then theirs, and
  /// τ̄ (each obstacle's forecast index) the largest of those forecast times. False under the other
  /// policies, and under the robust one when no maneuver was safe under all of them and ADJ decided.
  bool robust = false;
  /// True when the input's drivable area constrained this step: given, and the ego started on it
  /// (`starts_on_drivable_area`). Every index and the command then keep to the area within T_h.
  bool on_drivable_area = false;
  /// False when `config.decision_only` returned u_nom without the indices: `selected_family`,
  /// `forecast_time`, `forecast_index`, the selected indices and each obstacle's `forecast_index`
  /// were not computed and hold their defaults.
  bool indices_computed = true;

  /// The column of the Maneuverability Map at this time (spec §6): every obstacle forecast with τ_i.
  std::vector<double> forecast_times;
  std::vector<double> mi_brake;
  std::vector<double> mi_accelerate;
  std::vector<std::uint8_t> excluded;      ///< τ_i > TTC

  double time_to_collision = 0.0;          ///< TTC [s], the earliest over all obstacles; ∞ for none
  double collision_time_step = 0.0;        ///< time step of the collision tests [s]
  std::vector<obstacle_assessment> obstacles;  ///< in input order
  std::optional<sample_snapshot> samples;  ///< when `config.record_samples`
  plan_work work;                          ///< what the fast path computed

  bool ok() const { return status == plan_status::ok; }
};

/// Why `input` cannot be planned on — the field, its value and what was expected — or nothing:
/// values that are not finite, out of order or out of range, and magnitudes beyond
/// `input_bounds.hpp`'s.
std::optional<std::string> validation_error(const plan_input& input);

/// One planning step with Maneuverability Maps (spec §3–§9): the fast path.
/// Pure: the same input gives the same result. Thread-safe.
plan_result plan(const plan_input& input);

namespace detail {
struct planning_cache;
}

/// The planner of one vehicle's consecutive steps: `plan(input)` returns exactly what
/// `mm::plan(input)` returns, bit for bit, and reuses what the previous call sampled when the ego's
/// speed, limits and footprint radius, the displacement horizon and the resolution are unchanged —
/// as they are while a vehicle cruises at a steady speed: the sampled displacement sets [AS−], [AS+]
/// (spec §3, whose cell areas cost a few thousand sines) and the ego's tree of maneuver blocks; it
/// also keeps the clearance fields' working memory from step to step (whatever the speed).
/// Holds that cache: use it from one thread at a time. Any planner may plan any vehicle (the
/// result never depends on what it planned before), so many vehicles at one speed can share one,
/// which keeps its cache in the processor's (the simulator keeps a few per thread, by speed).
class planner {
 public:
  planner();
  ~planner();
  planner(planner&&) noexcept;
  planner& operator=(planner&&) noexcept;
  planner(const planner&) = delete;
  planner& operator=(const planner&) = delete;

  plan_result plan(const plan_input& input);

 private:
  std::unique_ptr<detail::planning_cache> cache_;
};

}  // namespace mm
