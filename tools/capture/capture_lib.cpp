#include "mm/capture.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>

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
