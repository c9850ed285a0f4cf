// Plans on a saved planning input (`maneuvermap_capture --save`), without the simulation: prints the
// result's forecast time, command, work counts and map column, and with --repeat N plans N times in
// `plan_repeatedly`, so that instruction counts of one planning step can be taken with callgrind:
//
//   maneuvermap_replan FILE.json [--repeat N]
//   valgrind --tool=callgrind --toggle-collect='*plan_repeatedly*' maneuvermap_replan FILE.json --repeat 1
//
// (the count of the `plan_repeatedly` frame, divided by N, is what docs/performance.md reports).
#include <climits>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "mm/plan_input_json.hpp"
#include "mm/tool_cli.hpp"

namespace {

/// Plans on `input` `count` times and returns a sum of the indices (so that the calls are not dropped).
[[gnu::noinline]] double plan_repeatedly(const mm::plan_input& input, int count) {
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const mm::plan_result r = mm::plan(input);
    sum += r.mi_brake.empty() ? 0.0 : r.mi_brake.front() + r.mi_accelerate.front();
  }
  return sum;
}

int replan(const std::string& path, int repeat) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot read the file");
  mm::plan_input input;
  try {
    input = mm::capture::plan_input_from_json(nlohmann::json::parse(file));
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what() +
                             " (expected a planning input saved by maneuvermap_capture --save)");
  }
  if (repeat > 0) plan_repeatedly(input, repeat);
  const mm::plan_result r = mm::plan(input);
  if (!r.ok()) throw std::runtime_error(path + ": " + r.error);
  std::printf("forecast_time %.3f family %s command %.6f %.6f mode %s\n", r.forecast_time,
              std::string(mm::to_string(r.selected_family)).c_str(), r.command.acceleration, r.command.curvature,
              std::string(mm::to_string(r.mode)).c_str());
  std::printf("relevant %zu bound_checks %zu distances %zu refinements %zu assignments %zu\n", r.work.relevant_obstacles,
              r.work.bound_checks, r.work.distance_evaluations, r.work.refinements, r.work.assignments_evaluated);
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    std::printf("tau %.3f mi_brake %.4f mi_accelerate %.4f%s\n", r.forecast_times[i], r.mi_brake[i], r.mi_accelerate[i],
                r.excluded[i] ? " excluded" : "");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  int repeat = 0;
  CLI::App app{"Plans on a planning input saved by maneuvermap_capture --save, without the simulation: prints the\n"
               "result's forecast time, command, work counts and map column. With --repeat N it first plans N times\n"
               "in plan_repeatedly, for instruction counts with callgrind:\n"
               "  valgrind --tool=callgrind --toggle-collect='*plan_repeatedly*' \\\n"
               "    maneuvermap_replan FILE.json --repeat 1\n",
               "maneuvermap_replan"};
  app.add_option("FILE.json", path, "Planning input saved by maneuvermap_capture --save")
      ->required()
      ->check(CLI::ExistingFile);
  mm::tool_cli::add_whole(app, "--repeat", repeat, 0, INT_MAX, "Plan this many times in plan_repeatedly first (>= 0)");
  return mm::tool_cli::run(app, argc, argv, [&] { return replan(path, repeat); });
}
