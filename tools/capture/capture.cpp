// Finds the planning steps worth benchmarking in a scenario: runs it, and for every plan of the
// chosen planning vehicle prints the time, the number of obstacles handed to the planner, how many
// of them the planner kept (`relevant`, spec §9) and how many *interact* — take room away from
// the ego under some forecast time when planned alone — the smallest room max(MI−, MI+) over the
// forecast times, the planning mode and the planner's CPU time. The benchmarks (benchmarks/captured_inputs.cpp)
// replay a scenario to a time found here and plan on `simulation::planning_input` of that instant.
//
//   maneuvermap_capture SCENARIO [--agent NAME] [--set NAME=VALUE]... [--every K] [--from T] [--summary]
//   maneuvermap_capture SCENARIO --agent NAME [--set NAME=VALUE]... --at T --save FILE.json
//
// SCENARIO is a built-in name or a file. --every K prints every K-th plan only; --from T looks only
// at plans from time T [s] on (the run before is simulated, not counted); --summary prints
// only, per number of interacting obstacles, the step of least room (the strongest interaction)
// among the plans that still find a safe maneuver (mode other than near_crash). With --save it
// writes the planning input of NAME at time T instead (the benchmarks' replay of that instant,
// `mm::capture::replay`), as JSON that `maneuvermap_replan` plans on without the simulation.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"
#include "mm/capture.hpp"
#include "mm/scenario_options.hpp"
#include "mm/plan_input_json.hpp"
#include "mm/tool_cli.hpp"

namespace {

struct strongest {
  double time = 0.0;
  std::string agent;
  double room = 2.0;
  std::size_t relevant = 0;
};

/// The command line; the defaults are the tool's.
struct capture_options : mm::capture::scenario_options {
  std::size_t every = 1;
  double from = 0.0;
  std::optional<double> at;
  std::string save;
  bool summary = false;
};

/// --save: writes the planning input of the agent at --at as JSON.
int save_input(const capture_options& o, const mm::scenario_file::load_options& options) {
  mm::capture::check_planning_vehicle(mm::sim::simulation(mm::scenario_file::load(o.scenario, options).scenario),
                                      o.agent, o.scenario);
  const mm::plan_input input = mm::capture::replay({o.scenario, options.overrides, o.agent, *o.at});
  std::ofstream file(o.save);
  file << mm::capture::to_json(input).dump(1) << "\n";
  if (!file) throw std::runtime_error("--save " + o.save + ": cannot write the file");
  std::printf("%s: the planning input of %s at %.2f s (%zu obstacles)\n", o.save.c_str(), o.agent.c_str(), input.time,
              input.obstacles.size());
  return 0;
}

int capture(const capture_options& o) {
  const mm::scenario_file::load_options options = o.load_options();
  if (!o.save.empty()) return save_input(o, options);
  const std::string& agent = o.agent;
  const std::size_t every = o.every;
  const bool summary = o.summary;
  const double from = o.from;
  mm::sim::simulation sim(mm::scenario_file::load(o.scenario, options).scenario, mm::capture::every_core());
  if (!agent.empty()) mm::capture::check_planning_vehicle(sim, o.agent, o.scenario);
  std::map<std::size_t, strongest> by_interacting;
  std::size_t plans = 0;
  if (!summary) std::printf("t_s,agent,obstacles,relevant,interacting,min_room,mode,cpu_us\n");
  mm::sim::run(sim, [&](const mm::sim::simulation& s) {
    if (s.time() < from) return;
    for (mm::sim::agent_id id = 0; id < s.planning_vehicle_count(); ++id) {
      if (!agent.empty() && s.info(id).name != agent) continue;
      if (!s.planned_now(id)) continue;
      const auto input = s.planning_input(id);
      if (!input) continue;
      const mm::capture::interaction_count count = mm::capture::count_interactions(*input);
      const auto start = std::chrono::steady_clock::now();
      const mm::plan_result r = mm::plan(*input);
      const auto stop = std::chrono::steady_clock::now();
      const double cpu = std::chrono::duration<double, std::micro>(stop - start).count();
      const double room = mm::capture::smallest_room(r);
      strongest& best = by_interacting[count.interacting];
      if (r.mode != mm::planning_mode::near_crash && room < best.room) best = {s.time(), s.info(id).name, room, count.relevant};
      if (!summary && plans++ % every == 0) {
        std::printf("%.2f,%s,%zu,%zu,%zu,%.4f,%s,%.1f\n", s.time(), s.info(id).name.c_str(), input->obstacles.size(),
                    count.relevant, count.interacting, room, std::string(mm::to_string(r.mode)).c_str(), cpu);
      }
    }
  });
  std::printf("# strongest interaction per number of interacting obstacles: interacting,t_s,agent,relevant,min_room\n");
  for (const auto& [n, b] : by_interacting) {
    std::printf("# %zu,%.2f,%s,%zu,%.4f\n", n, b.time, b.agent.c_str(), b.relevant, b.room);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace cli = mm::tool_cli;
  capture_options o;
  CLI::App app{"Runs a scenario and prints, for every plan of its planning vehicles (or of --agent), the time, the\n"
               "obstacles handed to the planner, how many are relevant and how many interact, the smallest room\n"
               "max(MI-, MI+), the planning mode and the planner's CPU time [us]. With --save, writes the planning\n"
               "input of --agent at --at as JSON instead (for maneuvermap_replan and the benchmarks).\n",
               "maneuvermap_capture"};
  app.footer("Forms:\n"
             "  maneuvermap_capture SCENARIO [--agent NAME] [--set NAME=VALUE]... [--every K] [--from T] [--summary]\n"
             "  maneuvermap_capture SCENARIO --agent NAME [--set NAME=VALUE]... --at T --save FILE.json");
  mm::capture::add_scenario_options(app, o);
  CLI::Option* every =
      cli::add_whole(app, "--every", o.every, 1, cli::unbounded, "Print every K-th plan only (>= 1)", "K");
  CLI::Option* from =
      cli::add_real(app, "--from", o.from, cli::real_bound::non_negative, "s",
                    "Look only at plans from this time on [s] (>= 0; the run before is simulated, not counted)", "T");
  CLI::Option* summary = app.add_flag("--summary", o.summary,
                                      "Print only, per number of interacting obstacles, the plan of least room among "
                                      "those that find a safe maneuver (mode other than near_crash)");
  CLI::Option* at = cli::add_real(app, "--at", o.at, cli::real_bound::non_negative, "s",
                                  "With --save: the time of the planning input [s] (>= 0)", "T");
  CLI::Option* save = app.add_option("--save", o.save,
                                     "Write the planning input of --agent at --at to this JSON file instead")
                          ->type_name("FILE.json");
  save->needs("--agent")->needs(at)->excludes(every)->excludes(from)->excludes(summary);
  at->needs(save);
  return cli::run(app, argc, argv, [&] { return capture(o); });
}
