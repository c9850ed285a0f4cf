// maneuvermap_bench: the planner on fixed inputs captured from the built-in scenarios (from scratch,
// and with one mm::planner kept as a vehicle planning every step keeps it), the planner in the dense
// traffic of the 50-vehicle roundabout (a saved input), the reference planner on the one-obstacle
// input, one whole S3 run and the first 4 s of the 50-vehicle roundabout (docs/performance.md).
//
//   build/release/benchmarks/maneuvermap_bench [--whole-roundabout] [Google Benchmark flags]
//
// --whole-roundabout adds the roundabout's whole 20 s with two threads, once with the maps, once
// without, and once with only what the commands need (`run_options::decision_only`, as a sweep's
// runs; about two minutes each on the machine of docs/performance.md).
//
// Each case runs several repetitions and reports their median and their maximum; `worst_us`
// is the slowest single call seen in a repetition. The roundabout's `min` row holds the slowest
// repetition's real-time factor (its `max` row the fastest one's).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "captured_inputs.hpp"
#include "mm/plan_input_json.hpp"
#include "mm/planner.hpp"
#include "mm/reference_planner.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/memory.hpp"
#include "mm/sim/simulation.hpp"

namespace {

double largest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
double smallest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

/// The captured input of `interacting` obstacles, replayed once per process.
const mm::plan_input& input_with(std::size_t interacting) {
  static std::map<std::size_t, mm::plan_input> cache;
  auto it = cache.find(interacting);
  if (it == cache.end()) it = cache.emplace(interacting, mm::capture::replay(mm::bench::captured(interacting).point)).first;
  return it->second;
}

/// Runs `call` once per iteration, timing each call; reports the slowest as `worst_us`.
template <class Call>
void timed_loop(benchmark::State& state, Call&& call) {
  double worst = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(call());
    const auto stop = std::chrono::steady_clock::now();
    worst = std::max(worst, std::chrono::duration<double, std::micro>(stop - start).count());
  }
  state.counters["worst_us"] = worst;
}

/// Runs `mm::plan(in)` once per iteration; also reports the work of one call (`mm::plan_work`).
void timed_plan(benchmark::State& state, const mm::plan_input& in) {
  timed_loop(state, [&] { return mm::plan(in); });
  const mm::plan_work work = mm::plan(in).work;
  state.counters["relevant"] = static_cast<double>(work.relevant_obstacles);
  state.counters["bounds"] = static_cast<double>(work.bound_checks);
  state.counters["distances"] = static_cast<double>(work.distance_evaluations);
  state.counters["refinements"] = static_cast<double>(work.refinements);
  state.counters["translations"] = static_cast<double>(work.translation_minima);
  state.counters["assignments"] = static_cast<double>(work.assignments_evaluated);
}

/// False, with the case skipped with an error, when the replayed input `in` of `c` no longer has the
/// interacting obstacles it was captured with (scenarios can change).
bool still_interacting(benchmark::State& state, const mm::bench::captured_input& c, const mm::plan_input& in) {
  const std::size_t interacting = mm::capture::count_interactions(in).interacting;
  if (interacting == c.interacting) return true;
  state.SkipWithError(("the captured input has " + std::to_string(interacting) + " interacting obstacles, not " +
                       std::to_string(c.interacting) + ": capture it again (tools/capture)")
                          .c_str());
  return false;
}

/// The captured input of `state.range(0)` interacting obstacles, or null (the case skipped with an
/// error) when the replayed input no longer has them.
const mm::plan_input* checked_input(benchmark::State& state) {
  const auto wanted = static_cast<std::size_t>(state.range(0));
  const mm::plan_input& in = input_with(wanted);
  return still_interacting(state, mm::bench::captured(wanted), in) ? &in : nullptr;
}

void plan_case(benchmark::State& state) {
  if (const mm::plan_input* in = checked_input(state)) timed_plan(state, *in);
}

/// S3's costliest step (`costliest_one_obstacle`), replayed once per process and checked like the
/// `plan` inputs.
void plan_costliest_case(benchmark::State& state) {
  const mm::bench::captured_input& c = mm::bench::costliest_one_obstacle();
  static const mm::plan_input in = mm::capture::replay(c.point);
  if (still_interacting(state, c, in)) timed_plan(state, in);
}

/// The dense-traffic input (`mm::bench::dense_following`), read from its saved file once per process;
/// null, with the case skipped with an error, when the file cannot be read.
const mm::plan_input* following_input(benchmark::State& state) {
  static const std::pair<mm::plan_input, std::string> loaded = [] {
    const std::string path = std::string(MM_SOURCE_DIR) + "/" + mm::bench::dense_following().file;
    try {
      std::ifstream file(path);
      if (!file) throw std::runtime_error("cannot read the file");
      return std::pair{mm::capture::plan_input_from_json(nlohmann::json::parse(file)), std::string()};
    } catch (const std::exception& e) {
      return std::pair{mm::plan_input{}, path + ": " + e.what()};
    }
  }();
  if (loaded.second.empty()) return &loaded.first;
  state.SkipWithError(loaded.second.c_str());
  return nullptr;
}

void plan_following_case(benchmark::State& state) {
  if (const mm::plan_input* in = following_input(state)) timed_plan(state, *in);
}

void planner_following_case(benchmark::State& state) {
  const mm::plan_input* in = following_input(state);
  if (in == nullptr) return;
  mm::planner planner;
  timed_loop(state, [&] { return planner.plan(*in); });
}

/// The dense-traffic input with no obstacles but the first `state.range(0)` of its relevant
/// neighbours that no maneuver comes near (`mm::capture::inert_obstacles`; 15 of its 40), planned by
/// one `mm::planner` as a vehicle plans: what such neighbours add to a step (issue 5: neighbours that
/// cannot interact must cost nothing). With `far`, the same neighbours moved 1 km away, where the
/// relevance test (spec §9) drops them. Skipped with an error when the input has fewer.
void planner_quiet_neighbours(benchmark::State& state, bool far) {
  const mm::plan_input* in = following_input(state);
  if (in == nullptr) return;
  static const std::vector<std::size_t> inert = mm::capture::inert_obstacles(*in);
  const auto count = static_cast<std::size_t>(state.range(0));
  if (inert.size() < count) {
    state.SkipWithError(("the dense-traffic input has " + std::to_string(inert.size()) +
                         " neighbours that no maneuver comes near, not " + std::to_string(count))
                            .c_str());
    return;
  }
  mm::plan_input quiet = *in;
  quiet.obstacles.clear();
  for (std::size_t k = 0; k < count; ++k) {
    mm::obstacle_track track = in->obstacles[inert[k]];
    if (far) {
      for (mm::observation& o : track.history) o.pose.position = o.pose.position + mm::vec2{1000.0, 0.0};
    }
    quiet.obstacles.push_back(std::move(track));
  }
  mm::planner planner;
  timed_loop(state, [&] { return planner.plan(quiet); });
  state.counters["relevant"] = static_cast<double>(mm::plan(quiet).work.relevant_obstacles);
}

void planner_inert_neighbours_case(benchmark::State& state) { planner_quiet_neighbours(state, false); }
void planner_far_neighbours_case(benchmark::State& state) { planner_quiet_neighbours(state, true); }

/// The captured input planned by one `mm::planner` every iteration, as a vehicle planning every step
/// at an unchanged speed does: each call starts the planner again (its result is `mm::plan`'s, bit
/// for bit) but keeps the sampled sets, the tree of blocks and the placements in the ego's frame.
void planner_case(benchmark::State& state) {
  const mm::plan_input* in = checked_input(state);
  if (in == nullptr) return;
  mm::planner planner;
  timed_loop(state, [&] { return planner.plan(*in); });
}

/// The one-obstacle input with `state.range(0)` forecast times spread over the same 0..2 s.
void plan_forecast_grid(benchmark::State& state) {
  mm::plan_input in = input_with(1);
  const double last = in.config.forecast_step * static_cast<double>(in.config.forecast_count - 1);
  in.config.forecast_count = static_cast<std::size_t>(state.range(0));
  in.config.forecast_step = last / static_cast<double>(in.config.forecast_count - 1);
  timed_plan(state, in);
}

/// The one-obstacle input sampled with `state.range(0)` accelerations × `state.range(1)`
/// curvatures per family.
void plan_resolution(benchmark::State& state) {
  mm::plan_input in = input_with(1);
  in.config.resolution.accelerations = static_cast<std::size_t>(state.range(0));
  in.config.resolution.curvatures = static_cast<std::size_t>(state.range(1));
  timed_plan(state, in);
}

void plan_reference_case(benchmark::State& state) {
  const mm::plan_input& in = input_with(static_cast<std::size_t>(state.range(0)));
  timed_loop(state, [&] { return mm::plan_reference(in); });
}

/// One cell of the paper's Table 1: a whole S3 run, loaded from the scenario file.
void table1_cell(benchmark::State& state) {
  const mm::scenario_file::loaded_scenario loaded =
      mm::scenario_file::load_file(std::string(MM_SOURCE_DIR) + "/scenarios/s3-left-turn.yaml");
  timed_loop(state, [&] {
    mm::sim::simulation sim(loaded.scenario);
    mm::sim::run(sim);
    return sim.time();
  });
}

/// The scenario s6-busy-roundabout for its first `seconds` with `options`, timed.
void time_busy_roundabout(benchmark::State& state, double seconds, const mm::sim::run_options& options) {
  mm::scenario_file::loaded_scenario loaded = mm::scenario_file::load("s6-busy-roundabout");
  loaded.scenario.duration = seconds;
  double simulated = 0.0;
  double wall = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    mm::sim::simulation sim(loaded.scenario, options);
    mm::sim::run(sim);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    simulated += sim.time();
  }
  state.counters["real_time_factor"] = simulated / wall;
}

/// The many-agent scenario (s6-busy-roundabout: 50 planning vehicles) for its first
/// `state.range(1)` simulated seconds with `state.range(0)` planning threads, recording every
/// vehicle's Maneuverability Map when `state.range(2)` is 1 (what `maneuvermap run` writes) or
/// only the decisions when 0 (`run_options::map_columns`, what a sweep's runs do: the same run,
/// bit for bit); reports the real-time factor (simulated time over wall time) at its 100 Hz step.
void busy_roundabout(benchmark::State& state) {
  mm::sim::run_options options;
  options.jobs = static_cast<std::size_t>(state.range(0));
  options.map_columns = state.range(2) != 0;
  time_busy_roundabout(state, static_cast<double>(state.range(1)), options);
}

/// As `busy_roundabout` without the maps, and with `run_options::decision_only` (what a sweep's runs
/// do since 2026-12-07: the same run, bit for bit): a step whose nominal maneuver is proven safe
/// under every forecast time computes no index.
void busy_roundabout_decision_only(benchmark::State& state) {
  mm::sim::run_options options;
  options.jobs = static_cast<std::size_t>(state.range(0));
  options.map_columns = false;
  options.decision_only = true;
  time_busy_roundabout(state, static_cast<double>(state.range(1)), options);
}

/// `repetitions` repetitions, reported as their mean, median, spread and slowest (`max`) only.
benchmark::internal::Benchmark* repeated(benchmark::internal::Benchmark* b, int repetitions) {
  return b->Repetitions(repetitions)->ComputeStatistics("max", largest)->ReportAggregatesOnly(true);
}

void register_all(bool whole_roundabout) {
  for (const mm::bench::captured_input& c : mm::bench::captured_inputs()) {
    repeated(benchmark::RegisterBenchmark("plan", plan_case), 5)
        ->ArgName("obstacles")
        ->Arg(static_cast<long>(c.interacting))
        ->Unit(benchmark::kMicrosecond);
  }
  repeated(benchmark::RegisterBenchmark("plan_costliest", plan_costliest_case), 5)
      ->ArgName("obstacles")
      ->Arg(1)
      ->Unit(benchmark::kMicrosecond);
  for (const mm::bench::captured_input& c : mm::bench::captured_inputs()) {
    if (c.interacting == 0) continue;
    repeated(benchmark::RegisterBenchmark("planner", planner_case), 5)
        ->ArgName("obstacles")
        ->Arg(static_cast<long>(c.interacting))
        ->Unit(benchmark::kMicrosecond);
  }
  for (const long count : {5, 9, 17, 33}) {
    repeated(benchmark::RegisterBenchmark("plan_forecast_grid", plan_forecast_grid), 5)
        ->ArgName("forecast_count")
        ->Arg(count)
        ->Unit(benchmark::kMicrosecond);
  }
  for (const auto& [accelerations, curvatures] : {std::pair{11L, 15L}, {15L, 21L}, {21L, 31L}, {31L, 41L}}) {
    repeated(benchmark::RegisterBenchmark("plan_resolution", plan_resolution), 5)
        ->ArgNames({"accelerations", "curvatures"})
        ->Args({accelerations, curvatures})
        ->Unit(benchmark::kMicrosecond);
  }
  repeated(benchmark::RegisterBenchmark("plan_following", plan_following_case), 5)->Unit(benchmark::kMicrosecond);
  repeated(benchmark::RegisterBenchmark("planner_following", planner_following_case), 5)
      ->Unit(benchmark::kMicrosecond);
  repeated(benchmark::RegisterBenchmark("planner_inert_neighbours", planner_inert_neighbours_case), 5)
      ->ArgName("count")
      ->Arg(1)
      ->Arg(15)
      ->Unit(benchmark::kMicrosecond);
  repeated(benchmark::RegisterBenchmark("planner_far_neighbours", planner_far_neighbours_case), 5)
      ->ArgName("count")
      ->Arg(15)
      ->Unit(benchmark::kMicrosecond);
  repeated(benchmark::RegisterBenchmark("plan_reference", plan_reference_case), 3)
      ->ArgName("obstacles")
      ->Arg(1)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  repeated(benchmark::RegisterBenchmark("sim/table1_cell", table1_cell), 3)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  // Three runs each: the median and, as `min`, the slowest run's real-time factor (the worst case).
  repeated(benchmark::RegisterBenchmark("sim/busy_roundabout", busy_roundabout), 3)
      ->ComputeStatistics("min", smallest)
      ->ArgNames({"jobs", "seconds", "maps"})
      ->Args({1, 4, 1})
      ->Args({2, 4, 1})
      ->Args({1, 4, 0})
      ->Args({2, 4, 0})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  if (whole_roundabout) {
    // The whole run, once each: the dense traffic of its later seconds costs far more than its start.
    benchmark::RegisterBenchmark("sim/busy_roundabout", busy_roundabout)
        ->ArgNames({"jobs", "seconds", "maps"})
        ->Args({2, 20, 1})
        ->Args({2, 20, 0})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
    benchmark::RegisterBenchmark("sim/busy_roundabout_decision_only", busy_roundabout_decision_only)
        ->ArgNames({"jobs", "seconds"})
        ->Args({2, 20})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  mm::sim::retain_freed_memory();  // as the command line does, so that sim/* measure what it runs
  bool whole_roundabout = false;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--whole-roundabout") == 0) {
      whole_roundabout = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  register_all(whole_roundabout);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
