#include "mm/capture.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>

#include "mm/maneuver_samples.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::capture {

double smallest_room(const plan_result& result) {
  double room = 1.0;
  for (std::size_t i = 0; i < result.forecast_times.size(); ++i) {
    room = std::min(room, std::max(result.mi_brake[i], result.mi_accelerate[i]));
  }
  return room;
}

void for_each_relevant(const plan_input& input, const plan_result& r,
                       const std::function<void(std::size_t, const ego_sweep&, const forecast_obstacle&)>& each) {
  const planner_config& config = input.config;
  const maneuver nominal = clamp_to_limits(input.nominal, input.ego.speed, input.ego.limits);
  const maneuver_samples samples =
      sample_maneuvers(input.ego, nominal.curvature, config.displacement_horizon, config.resolution, false, false);
  const collision_window window{config.displacement_horizon, config.collision_window, r.collision_time_step,
                                config.safety_margin};
  const ego_sweep sweep(input.ego, samples, window);
  for (std::size_t j = 0; j < input.obstacles.size(); ++j) {
    if (r.obstacles[j].relevant) each(j, sweep, {r.obstacles[j].motion, input.obstacles[j].shape});
  }
}

std::vector<std::size_t> inert_obstacles(const plan_input& input) {
  const plan_result r = plan(input);
  std::vector<std::size_t> inert;
  for_each_relevant(input, r, [&](std::size_t j, const ego_sweep& sweep, const forecast_obstacle& obstacle) {
    if (clearance_field(sweep, obstacle, r.forecast_times, planner_clearance_cap).inert()) inert.push_back(j);
  });
  return inert;
}

sim::run_options every_core() {
  sim::run_options run;
  run.jobs = std::max(1U, std::thread::hardware_concurrency());
  return run;
}

void check_planning_vehicle(const sim::simulation& sim, const std::string& agent, const std::string& scenario) {
  const auto id = sim.find(agent);
  if (id && *id < sim.planning_vehicle_count()) return;
  std::string names;
  for (sim::agent_id i = 0; i < sim.planning_vehicle_count(); ++i) {
    names += (names.empty() ? "" : ", ") + sim.info(i).name;
  }
  throw std::runtime_error("--agent " + agent + ": no planning vehicle of that name in " + scenario +
                           " (expected one of: " + names + ")");
}

interaction_count count_interactions(const plan_input& input) {
  interaction_count count;
  const plan_result all = plan(input);
  for (std::size_t j = 0; j < input.obstacles.size(); ++j) {
    if (!all.obstacles[j].relevant) continue;
    ++count.relevant;
    plan_input alone = input;
    alone.obstacles = {input.obstacles[j]};
    if (smallest_room(plan(alone)) < 1.0) ++count.interacting;
  }
  return count;
}

plan_input replay(const capture_point& point) {
  scenario_file::load_options options;
  options.overrides = point.overrides;
  sim::simulation sim(scenario_file::load(point.scenario, options).scenario, every_core());
  const auto id = sim.find(point.agent);
  if (!id || *id >= sim.planning_vehicle_count()) {
    throw std::runtime_error(point.scenario + ": no planning vehicle called " + point.agent);
  }
  const double dt = sim.definition().time_step;
  while (!sim.ended() && sim.time() < point.time - 1e-6 * dt) sim.step();
  auto input = sim.planning_input(*id);
  if (!input || sim.time() < point.time - 1e-6 * dt) {
    throw std::runtime_error(point.scenario + ": " + point.agent + " is not in the world at t = " +
                             std::to_string(point.time) + " s");
  }
  return std::move(*input);
}

}  // namespace mm::capture
