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
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"
#include "mm/capture.hpp"
#include "mm/plan_input_json.hpp"

namespace {

struct strongest {
  double time = 0.0;
  std::string agent;
  double room = 2.0;
  std::size_t relevant = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: maneuvermap_capture SCENARIO [--agent NAME] [--set NAME=VALUE]... [--every K] [--from T] [--summary]\n"
                         "       maneuvermap_capture SCENARIO --agent NAME [--set NAME=VALUE]... --at T --save FILE.json\n");
    return 2;
  }
  std::string agent;
  std::size_t every = 1;
  bool summary = false;
  double from = 0.0;
  double at = -1.0;
  std::string save;
  mm::scenario_file::load_options options;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--agent" && i + 1 < argc) {
      agent = argv[++i];
    } else if (arg == "--every" && i + 1 < argc) {
      every = static_cast<std::size_t>(std::max(1, std::atoi(argv[++i])));
    } else if (arg == "--from" && i + 1 < argc) {
      from = std::atof(argv[++i]);
    } else if (arg == "--at" && i + 1 < argc) {
      at = std::atof(argv[++i]);
    } else if (arg == "--save" && i + 1 < argc) {
      save = argv[++i];
    } else if (arg == "--summary") {
      summary = true;
    } else if (arg == "--set" && i + 1 < argc) {
      const auto o = mm::scenario_file::parse_override(argv[++i]);
      if (!o) {
        std::fprintf(stderr, "bad --set %s\n", argv[i]);
        return 2;
      }
      options.overrides.push_back(*o);
    } else {
      std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  if (!save.empty()) {
    if (agent.empty() || at < 0.0) {
      std::fprintf(stderr, "--save needs --agent NAME and --at T (T >= 0)\n");
      return 2;
    }
    const mm::plan_input input = mm::capture::replay({argv[1], options.overrides, agent, at});
    std::ofstream file(save);
    file << mm::capture::to_json(input).dump(1) << "\n";
    if (!file) {
      std::fprintf(stderr, "%s: cannot write\n", save.c_str());
      return 1;
    }
    std::printf("%s: the planning input of %s at %.2f s (%zu obstacles)\n", save.c_str(), agent.c_str(), input.time,
                input.obstacles.size());
    return 0;
  }
  mm::sim::simulation sim(mm::scenario_file::load(argv[1], options).scenario, mm::capture::every_core());
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
