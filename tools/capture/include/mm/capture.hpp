#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mm/collision_sets.hpp"
#include "mm/planner.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::capture {

/// How many obstacles of a planning input matter.
struct interaction_count {
  std::size_t relevant = 0;     ///< kept by the planner: can reach some maneuver within T_c (spec §9)
  std::size_t interacting = 0;  ///< planned alone, it takes room from the ego under some forecast time
};

/// Simulation options that plan on every core: planning threads change nothing in a run
/// (`sim::run_options::jobs`), only how long it takes.
sim::run_options every_core();

/// Throws std::runtime_error when `agent` is not a planning vehicle of `sim` (of `scenario`), naming
/// the option (--agent) and the planning vehicles there are.
void check_planning_vehicle(const sim::simulation& sim, const std::string& agent, const std::string& scenario);

/// Counts the relevant and the interacting obstacles of `input` (one extra plan per relevant obstacle).
interaction_count count_interactions(const plan_input& input);

/// Smallest room max(MI−, MI+) over the forecast times of a plan.
double smallest_room(const plan_result& result);

/// Calls `each(j, sweep, obstacle)` for every obstacle j that the plan `r` of `input` found
/// relevant, with the ego's sweep as that plan built it (its sampled sets, collision window and
/// forecast times) and the obstacle as it was forecast: what its clearance field is built from.
void for_each_relevant(const plan_input& input, const plan_result& r,
                       const std::function<void(std::size_t, const ego_sweep&, const forecast_obstacle&)>& each);

/// The relevant obstacles of `input` that no maneuver comes near (their clearance field is inert:
/// beyond the clearance cap at every time under every forecast time), as indices into
/// `input.obstacles`.
std::vector<std::size_t> inert_obstacles(const plan_input& input);

/// A planning step taken from a scenario: the scenario (built-in name or file), its parameter
/// overrides, the planning vehicle and the time at which its input is taken.
struct capture_point {
  std::string scenario;
  std::vector<std::pair<std::string, double>> overrides;
  std::string agent;
  double time = 0.0;  ///< [s], a multiple of the scenario's time step
};

/// Runs the scenario from its start to `point.time` (the first instant at or after it) and returns
/// what `point.agent` plans on then (`simulation::planning_input`). Deterministic. Throws
/// std::runtime_error when the agent does not exist or is not in the world at that time.
plan_input replay(const capture_point& point);

}  // namespace mm::capture
