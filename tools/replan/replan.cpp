// Plans on a saved planning input (`maneuvermap_capture --save`), without the simulation: prints the
// result's forecast time, command, work counts and map column, and with --repeat N plans N times in
// `plan_repeatedly`, so that instruction counts of one planning step can be taken with callgrind:
//
//   maneuvermap_replan FILE.json [--repeat N]
//   valgrind --tool=callgrind --toggle-collect='*plan_repeatedly*' maneuvermap_replan FILE.json --repeat 1
//
// (the count of the `plan_repeatedly` frame, divided by N, is what docs/performance.md reports).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "mm/plan_input_json.hpp"

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

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: maneuvermap_replan FILE.json [--repeat N]\n");
    return 2;
  }
  int repeat = 0;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  std::ifstream file(argv[1]);
  if (!file) {
    std::fprintf(stderr, "%s: cannot read\n", argv[1]);
    return 2;
  }
  mm::plan_input input;
  try {
    input = mm::capture::plan_input_from_json(nlohmann::json::parse(file));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 2;
  }
  if (repeat > 0) plan_repeatedly(input, repeat);
  const mm::plan_result r = mm::plan(input);
  if (!r.ok()) {
    std::fprintf(stderr, "%s: %s\n", argv[1], r.error.c_str());
    return 2;
  }
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
