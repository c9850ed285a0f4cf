// Plans on a saved planning input (`maneuvermap_capture --save`), without the simulation: prints the
// result's forecast time, command, work counts and map column, and with --repeat N plans N times in
// `plan_repeatedly`, so that instruction counts of one planning step can be taken with callgrind:
//
//   maneuvermap_replan FILE.json [--repeat N] [--fields N]
//   valgrind --tool=callgrind --toggle-collect='*plan_repeatedly*' maneuvermap_replan FILE.json --repeat 1
//
// (the count of the `plan_repeatedly` frame, divided by N, is what docs/performance.md reports).
// --reference prints the reference planner's result instead (maneuvermap_scenario_accuracy finds
// the inputs on which the two differ most).
// --fields N builds the clearance field of every relevant obstacle N times and prints its mean time.
// --proofs runs the command's continuous-time proof on the samples the sets call safe (why a step
// with room can be a near-crash: docs/method.md §4.5).
#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/capture.hpp"
#include "mm/collision.hpp"
#include "mm/collision_sets.hpp"
#include "mm/footprint.hpp"
#include "mm/plan_input_json.hpp"
#include "mm/reference_planner.hpp"
#include "mm/tool_cli.hpp"

namespace {

/// Plans on `input` `count` times and returns a sum of the indices (so that the calls are not dropped):
/// with `mm::plan`, from scratch each time, or with one `mm::planner` when `keep_planner`, as a
/// vehicle planning every step does (at an unchanged speed it keeps the sampled sets, the tree of
/// blocks and the placements in the ego's frame; the first call samples them).
[[gnu::noinline]] double plan_repeatedly(const mm::plan_input& input, int count, bool keep_planner) {
  double sum = 0.0;
  mm::planner planner;
  for (int i = 0; i < count; ++i) {
    const mm::plan_result r = keep_planner ? planner.plan(input) : mm::plan(input);
    sum += r.mi_brake.empty() ? 0.0 : r.mi_brake.front() + r.mi_accelerate.front();
  }
  return sum;
}

/// The clearance field of every relevant obstacle of `input`, as the plan `r` built it (its sampled
/// sets, collision window and forecast times), built `count` times: prints the obstacle's id,
/// distance [m], speed [m/s] and yaw rate [rad/s], the mean construction time [µs], whether it is
/// inert, and its sampled collisions summed over the forecast times. The first build also places the
/// ego's maneuvers (the sweep keeps them), as the plan's first field does.
void time_fields(const mm::plan_input& input, const mm::plan_result& r, int count) {
  mm::clearance_field::raster_scratch scratch;
  mm::capture::for_each_relevant(input, r, [&](std::size_t j, const mm::ego_sweep& sweep,
                                               const mm::forecast_obstacle& obstacle) {
    bool inert = false;
    std::size_t collisions = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < count; ++i) {
      const mm::clearance_field field(sweep, obstacle, r.forecast_times, mm::planner_clearance_cap, {},
                                      scratch);
      inert = field.inert();
      collisions = 0;
      for (std::size_t f = 0; f < r.forecast_times.size(); ++f) collisions += field.collisions(f).count();
    }
    const std::chrono::duration<double, std::micro> elapsed = std::chrono::steady_clock::now() - start;
    std::printf("field %u distance %.1f speed %.2f yaw_rate %.3f us %.1f inert %d collisions %zu\n",
                static_cast<unsigned>(input.obstacles[j].id),
                mm::norm(obstacle.motion.pose.position - input.ego.pose.position), obstacle.motion.speed,
                obstacle.motion.yaw_rate, elapsed.count() / count, inert ? 1 : 0, collisions);
  });
}

/// The command's continuous-time proof (`mm::verified_collision_free` at
/// `mm::command_proof_resolution`, docs/method.md §4.5: the ADJ and constant policies' proof,
/// without the road constraint's) on every sample that the sets of the plan of `input` call safe
/// under its selected forecast times: prints how many there are, how many the speed bound proves
/// (the planner's first try) and how many the translation bound does (its second, before a
/// near-crash), and for each relevant obstacle that some are proven against by neither, how many
/// and their closest pass outside the margin [m] (the least signed distance − margin, sampled every
/// 0.1 ms over [0, T_c]). When the sets have room but the step is a near-crash, this shows the
/// proof's resolution at work.
void prove_safe_samples(mm::plan_input input) {
  input.config.record_samples = true;
  const mm::plan_result r = mm::plan(input);
  if (!r.ok() || !r.samples) throw std::runtime_error("--proofs: the plan recorded no samples: " + r.error);
  const mm::planner_config& c = input.config;
  const mm::collision_window window{c.displacement_horizon, c.collision_window, r.collision_time_step,
                                    c.safety_margin};
  std::vector<mm::forecast_obstacle> obstacles;
  std::vector<double> taus;
  std::vector<std::uint32_t> ids;
  mm::capture::for_each_relevant(input, r, [&](std::size_t j, const mm::ego_sweep&, const mm::forecast_obstacle& o) {
    obstacles.push_back(o);
    taus.push_back(r.forecast_times[r.obstacles[j].forecast_index]);
    ids.push_back(r.obstacles[j].id);
  });
  const mm::sample_snapshot& samples = *r.samples;
  std::size_t safe = 0;
  std::size_t by_speed = 0;
  std::size_t by_translation = 0;
  std::vector<std::size_t> failed(obstacles.size(), 0);
  std::vector<double> closest(obstacles.size(), std::numeric_limits<double>::infinity());
  const auto steps = static_cast<int>(std::llround(c.collision_window / 1e-4));
  for (std::size_t m = 0; m < samples.maneuvers.size(); ++m) {
    if (!samples.safe_selected[m]) continue;
    ++safe;
    const mm::maneuver& u = samples.maneuvers[m];
    const auto proven = [&](std::span<const mm::forecast_obstacle> those, std::span<const double> their_taus,
                            mm::proof_steps stepping) {
      return mm::verified_collision_free(input.ego, u, those, their_taus, window, mm::command_proof_resolution,
                                         stepping);
    };
    by_speed += proven(obstacles, taus, mm::proof_steps::speed_bound) ? 1 : 0;
    if (proven(obstacles, taus, mm::proof_steps::translation_bound)) {
      ++by_translation;
      continue;
    }
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      if (proven(std::span(&obstacles[k], 1), std::span(&taus[k], 1), mm::proof_steps::translation_bound)) continue;
      ++failed[k];
      for (int i = 0; i <= steps; ++i) {
        const double t = std::min(i * 1e-4, c.collision_window);
        const mm::pose ego = mm::maneuver_pose(input.ego.pose, input.ego.speed, u, t, c.displacement_horizon,
                                               input.ego.limits.speed_cap);
        const mm::pose obstacle = mm::forecast_pose(obstacles[k].motion, taus[k], t);
        closest[k] = std::min(closest[k], mm::signed_distance(mm::place(input.ego.shape, ego),
                                                              mm::place(obstacles[k].shape, obstacle)) -
                                              c.safety_margin);
      }
    }
  }
  std::printf("proof safe_by_sets %zu speed_bound %zu translation_bound %zu\n", safe, by_speed, by_translation);
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    if (failed[k] > 0) {
      std::printf("proof_fails obstacle %u samples %zu closest %.4f\n", static_cast<unsigned>(ids[k]), failed[k],
                  closest[k]);
    }
  }
}

int replan(const std::string& path, int repeat, int fields, bool keep_planner, bool reference, bool proofs) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot read the file");
  mm::plan_input input;
  try {
    input = mm::capture::plan_input_from_json(nlohmann::json::parse(file));
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what() +
                             " (expected a planning input saved by maneuvermap_capture --save)");
  }
  if (repeat > 0) plan_repeatedly(input, repeat, keep_planner);
  const mm::plan_result r = reference ? mm::plan_reference(input) : mm::plan(input);
  if (!r.ok()) throw std::runtime_error(path + ": " + r.error);
  std::printf("forecast_time %.3f family %s command %.6f %.6f mode %s\n", r.forecast_time,
              std::string(mm::to_string(r.selected_family)).c_str(), r.command.acceleration, r.command.curvature,
              std::string(mm::to_string(r.mode)).c_str());
  std::printf("relevant %zu bound_checks %zu distances %zu refinements %zu translations %zu assignments %zu\n",
              r.work.relevant_obstacles, r.work.bound_checks, r.work.distance_evaluations, r.work.refinements,
              r.work.translation_minima, r.work.assignments_evaluated);
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    std::printf("tau %.3f mi_brake %.4f mi_accelerate %.4f%s\n", r.forecast_times[i], r.mi_brake[i], r.mi_accelerate[i],
                r.excluded[i] ? " excluded" : "");
  }
  if (fields > 0) time_fields(input, reference ? mm::plan(input) : r, fields);
  if (proofs) prove_safe_samples(input);
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
  int fields = 0;
  mm::tool_cli::add_whole(app, "--fields", fields, 0, INT_MAX,
                          "Also build the clearance field of every relevant obstacle this many times and print its "
                          "mean time [us], whether it is inert and its sampled collisions (>= 0)");
  bool keep_planner = false;
  app.add_flag("--planner", keep_planner,
               "Plan the --repeat times with one mm::planner, as a vehicle planning every step does, instead of "
               "mm::plan from scratch");
  bool reference = false;
  app.add_flag("--reference", reference,
               "Print the reference planner's result (mm::plan_reference at its default resolution, spec §11) "
               "instead of the fast planner's");
  bool proofs = false;
  app.add_flag("--proofs", proofs,
               "Also run the command's continuous-time proof on every sample the fast planner's sets call safe "
               "under its selected forecast times, and print how many the speed bound proves (the planner's "
               "first try), how many the translation bound does (its second) and, per obstacle, how many neither "
               "does and their closest pass outside the margin [m]");
  return mm::tool_cli::run(app, argc, argv,
                           [&] { return replan(path, repeat, fields, keep_planner, reference, proofs); });
}
