#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "mm/commonroad/scenario.hpp"
#include "mm/maneuver.hpp"
#include "mm/planner.hpp"

namespace mm::commonroad {

/// A road user that cannot be measured (unknown id, a pedestrian, a static obstacle), or a
/// recording the planner refuses: the message says which and why.
class measure_error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// How a recorded road user is measured (docs/commonroad.md).
struct measure_options {
  std::uint32_t agent = 0;  ///< the measured road user: a dynamic obstacle that is not a pedestrian
  planner_config config;    ///< forecast grid, resolution, policy (spec §4–§9)
  /// The measured vehicle's limits (spec §3). Its speed cap is raised to its largest recorded
  /// speed where that is higher, so that every recorded state is a valid ego state.
  ego_limits limits;
  /// The road constraint (spec §5): at each step the road user keeps its maneuvers on this area
  /// when it starts the step on it (`plan_result::on_drivable_area`); e.g. `lanelet_polygons`.
  /// None: no road constraint.
  std::shared_ptr<const mm::drivable_area> drivable_area;
};

/// The planner's view of the measured road user at one of its recorded steps k, at time t_k = k·Δt.
struct measured_step {
  std::int64_t step = 0;
  double time = 0.0;       ///< t_k [s]
  ego_state ego;           ///< its recorded pose (shape centre, heading wrapped to (−π, π]) and speed max(v_k, 0)
  maneuver recorded;  ///< what it did over the next step: `recorded_maneuver`, the planner's u_nom
  std::vector<std::uint32_t> obstacle_ids;  ///< the road users it planned against, in `result.obstacles` order
  plan_result result;                       ///< the Maneuverability Map column, τ̄, the family, the choice
};

/// Every recorded step of one road user.
struct measurement {
  std::uint32_t agent = 0;
  std::vector<measured_step> steps;
};

/// The planning input of road user `options.agent` at its recorded step `step`: the ego as recorded
/// (above), and every other obstacle present at that step — static obstacles with their one state,
/// road users with their recorded states up to it within the history window (spec §4), the last at
/// t_k, from which the planner estimates their speed and yaw rate; a road user at its first
/// recorded state, from which nothing can be estimated, with its recorded speed and yaw rate as its
/// motion (yaw rate 0 when the file gives none). `ids` receives their ids in input order.
/// Throws `measure_error` when the agent cannot be measured or is not recorded at `step`.
plan_input planning_input(const scenario& s, const measure_options& options, std::int64_t step,
                          std::vector<std::uint32_t>* ids = nullptr);

/// Plans road user `options.agent` at every one of its recorded steps with one kept `mm::planner`
/// (what `mm::plan` gives at each step, bit for bit). The recording is not changed by the plans:
/// this measures the room to maneuver the road user had, not what the planner would have done next.
/// Throws `measure_error` as `planning_input` does, or with the planner's message on invalid input.
measurement measure(const scenario& s, const measure_options& options);

/// What road user `o` did over the step after its state `index`, as a maneuver (the planner's
/// u_nom, spec §8): a = (max(v_{k+1}, 0) − max(v_k, 0))/Δt [m/s²] and
/// κ = wrap(ψ_{k+1} − ψ_k)/|p_{k+1} − p_k| [1/m] (0 where it moved less than 1 mm); at its last
/// state those of the step before; (0, 0) with a single state. `dt` = Δt [s].
maneuver recorded_maneuver(const obstacle& o, std::size_t index, double dt);

/// The dynamic obstacles that can be measured: every one that is not a pedestrian, in file order.
std::vector<std::uint32_t> measurable_road_users(const scenario& s);

/// Throws `measure_error` saying why road user `agent` cannot be measured or replayed (no obstacle
/// has the id, a static obstacle, a pedestrian), with the ids that can; returns when it can.
void require_measurable(const scenario& s, std::uint32_t agent);

/// `measurable_road_users(s)` for a message that asks for a road user: the first 20 ids,
/// comma-separated, then "… (N in all)" when there are more; "none" when there is none.
std::string measurable_road_users_text(const scenario& s);

/// The obstacle that replays the ego of `problem` (docs/commonroad.md): the one with the problem's
/// id (OpenSCENARIO conversions), else id − 90000 (inD conversions), else the one whose first state
/// lies within 0.5 m of the problem's initial position at its initial step with a heading within
/// 0.1 rad and a speed within 0.5 m/s. Nothing when there is none, or when it is a pedestrian.
std::optional<std::uint32_t> recorded_ego(const scenario& s, const planning_problem& problem);

/// max(MI−, MI+) under the selected forecast times: the room to maneuver the step left the road
/// user, in [0, 1] (spec §7: the forecast time with the most room is selected).
double room(const plan_result& result);

}  // namespace mm::commonroad
