// Measures the fast planner against the reference planner (spec §11) on the planning steps of a
// scenario: runs it, and for every plan of its planning vehicles (or of --agent; every K-th with
// --every K) plans the same input with `mm::plan` and `mm::plan_reference`, and reports the
// largest |MI_fast − MI_reference| over forecast times and families, whether the selected
// forecast time and family agree where the reference's best candidate leads by more than 0.02, and,
// with one relevant obstacle, whether the fast planner's pick lies within 0.02 below the
// reference's in the reference's own indices (spec §11; `plan_comparison::pick_shortfall`).
//
//   maneuvermap_scenario_accuracy SCENARIO [--agent NAME] [--set NAME=VALUE]... [--every K]
//       [--from T] [--until T] [--jobs J] [--ref-accelerations A] [--ref-curvatures C]
//       [--ref-accelerations-1d A] [--ref-proof-resolution S] [--bound B] [--check] [--csv FILE]
//
// Where the reference's exhaustive forecast-time search would be too large (many turning
// neighbours, S6), the plan is compared by its map columns alone, both planners under the constant
// policy (the columns, every obstacle forecast with τ_i, do not depend on the policy).
//
// The run itself is the simulator's (the fast planner drives); the reference only plans on the
// inputs, `--jobs` of them at a time. With --check the exit code is 1 when a plan breaks the bound.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mm/capture.hpp"
#include "mm/displacement_set.hpp"
#include "mm/scenario_options.hpp"
#include "mm/plan_comparison.hpp"
#include "mm/reference_planner.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"
#include "mm/tool_cli.hpp"

namespace {

namespace pc = mm::plan_comparison;

/// The command line; the defaults are the tool's.
struct options : mm::capture::scenario_options {
  std::size_t every = 1;
  double from = 0.0;
  std::optional<double> until;
  std::size_t jobs = std::max(1U, std::thread::hardware_concurrency());
  /// The reference's default grid, with a finer proof: the ego of a scenario drives on the edge of
  /// its safe set (the cheapest safe maneuver), so many maneuvers of the next step pass within
  /// millimetres of an obstacle, where the default proof (≈ 2.5 mm) would count them as colliding.
  mm::reference_resolution reference{{41, 121}, 1e-6};
  double bound = 0.02;
  bool check = false;
  std::string csv;
  /// Every planning vehicle's sampling grid instead of the scenario's (--resolution AxC): which grid
  /// meets the bound on a scenario (docs/method.md §7).
  std::optional<mm::sampling_resolution> resolution;
};

/// One compared plan.
struct comparison {
  double time = 0.0;
  std::string agent;
  mm::plan_input input;
  std::size_t relevant = 0;
  bool compared = false;  ///< false: the reference refused the input
  /// The reference's exhaustive search would be too large: the map columns alone were compared,
  /// both planners under the constant policy (the columns do not depend on the policy).
  bool columns_only = false;
  pc::index_difference worst;
  double worst_tau = 0.0;  ///< [s]
  std::size_t fast_forecast = 0;
  std::size_t reference_forecast = 0;
  double fast_tau = 0.0;       ///< τ̄ [s]
  double reference_tau = 0.0;  ///< τ̄ [s]
  mm::family fast_family = mm::family::brake;
  mm::family reference_family = mm::family::brake;
  double forecast_margin = 0.0;  ///< the reference's
  double family_margin = 0.0;    ///< the reference's
  double selected_room_difference = 0.0;  ///< |max(MI±_selected) fast − reference|
  /// With one relevant obstacle: how far the fast planner's pick (τ̄, family) lies below the
  /// reference's in the reference's own indices, MI_ref(pick_ref) − MI_ref(pick_fast) (0 when they
  /// agree); 0 with several (the reference's indices under the fast planner's assignment are not
  /// computed).
  double pick_shortfall = 0.0;
  double fast_ms = 0.0;
  double reference_ms = 0.0;
};

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double selected_room(const mm::plan_result& r) { return std::max(r.mi_brake_selected, r.mi_accelerate_selected); }

void compare(comparison& c, const mm::reference_resolution& reference) {
  c.input.config.map_column = true;
  c.input.config.record_samples = false;
  auto start = std::chrono::steady_clock::now();
  const mm::plan_result fast = mm::plan(c.input);
  c.fast_ms = milliseconds_since(start);
  if (!fast.ok()) throw std::runtime_error("the fast planner refused the input: " + fast.error);
  c.relevant = pc::relevant_obstacles(fast);
  start = std::chrono::steady_clock::now();
  const mm::plan_result ref = mm::plan_reference(c.input, reference);
  c.reference_ms = milliseconds_since(start);
  if (!ref.ok() && ref.error.rfind("config.max_exhaustive_assignments", 0) == 0) {
    // Every obstacle forecast with τ_i, as a map column is, needs no search: under the constant
    // policy neither planner searches, and the columns are compared alone.
    c.input.config.policy = {mm::forecast_policy_kind::constant, 0.0};
    const mm::plan_result fast_column = mm::plan(c.input);
    start = std::chrono::steady_clock::now();
    const mm::plan_result ref_column = mm::plan_reference(c.input, reference);
    c.reference_ms += milliseconds_since(start);
    c.input = {};
    if (!fast_column.ok() || !ref_column.ok()) {
      throw std::runtime_error("a planner refused the input under the constant policy: " + fast_column.error +
                               ref_column.error);
    }
    if (fast_column.mi_brake != fast.mi_brake || fast_column.mi_accelerate != fast.mi_accelerate) {
      throw std::runtime_error("the fast planner's map column depends on the policy");
    }
    c.compared = true;
    c.columns_only = true;
    c.worst = pc::largest_index_difference(fast_column, ref_column);
    c.worst_tau = ref_column.forecast_times[c.worst.forecast];
    return;
  }
  c.input = {};  // the history of every obstacle: not kept once planned on
  if (!ref.ok()) throw std::runtime_error("the reference planner refused the input: " + ref.error);
  c.compared = true;
  c.worst = pc::largest_index_difference(fast, ref);
  c.worst_tau = ref.forecast_times[c.worst.forecast];
  c.fast_tau = fast.forecast_time;
  c.reference_tau = ref.forecast_time;
  c.fast_forecast = fast.forecast_index;
  c.reference_forecast = ref.forecast_index;
  c.fast_family = fast.selected_family;
  c.reference_family = ref.selected_family;
  c.forecast_margin = pc::forecast_time_margin(ref);
  c.family_margin = pc::family_margin(ref);
  c.selected_room_difference = std::abs(selected_room(fast) - selected_room(ref));
  if (c.relevant == 1) c.pick_shortfall = pc::pick_shortfall(fast, ref);
}

/// Compares `pending` on `jobs` threads.
void compare_all(std::vector<comparison>& pending, std::size_t first, const options& o) {
  std::atomic<std::size_t> next{first};
  std::vector<std::string> failures(o.jobs);
  const auto work = [&](std::size_t worker) {
    for (std::size_t k = next++; k < pending.size(); k = next++) {
      try {
        compare(pending[k], o.reference);
      } catch (const std::exception& e) {
        failures[worker] = pending[k].agent + " at " + std::to_string(pending[k].time) + " s: " + e.what();
        next = pending.size();
      }
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < o.jobs; ++w) threads.emplace_back(work, w);
  work(0);
  for (std::thread& t : threads) t.join();
  for (const std::string& f : failures) {
    if (!f.empty()) throw std::runtime_error(f);
  }
}

/// The family's name, as `mm::to_string` gives it.
std::string name_of(mm::family f) { return std::string(mm::to_string(f)); }

/// The value at quantile q of sorted `values` (nearest rank), 0 when there are none.
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

int measure(const options& o) {
  const mm::scenario_file::load_options load = o.load_options();
  mm::sim::scenario scenario = mm::scenario_file::load(o.scenario, load).scenario;
  if (o.resolution) {
    for (mm::sim::planning_vehicle& v : scenario.planning_vehicles) v.planner.resolution = *o.resolution;
  }
  mm::sim::simulation sim(std::move(scenario), mm::capture::every_core());
  if (!o.agent.empty()) mm::capture::check_planning_vehicle(sim, o.agent, o.scenario);
  std::vector<comparison> plans;
  std::size_t seen = 0;
  std::size_t done = 0;
  const std::size_t batch = 16 * o.jobs;
  mm::sim::run(sim, [&](const mm::sim::simulation& s) {
    if (s.time() < o.from || (o.until && s.time() > *o.until)) return;
    for (mm::sim::agent_id id = 0; id < s.planning_vehicle_count(); ++id) {
      if (!o.agent.empty() && s.info(id).name != o.agent) continue;
      if (!s.planned_now(id) || seen++ % o.every != 0) continue;
      auto input = s.planning_input(id);
      if (!input) continue;
      comparison& c = plans.emplace_back();
      c.time = s.time();
      c.agent = s.info(id).name;
      c.input = std::move(*input);
    }
    if (plans.size() - done >= batch) {
      compare_all(plans, done, o);
      done = plans.size();
    }
  });
  compare_all(plans, done, o);

  std::vector<double> worst;  // of the compared plans with a relevant obstacle (without one both give 1)
  const comparison* largest = nullptr;
  std::size_t compared = 0, interacting = 0, several = 0, columns_only = 0, over = 0;
  std::size_t forecast_judged = 0, forecast_disagreements = 0, family_judged = 0, family_disagreements = 0;
  std::size_t picks_judged = 0, picks_below = 0;
  double largest_room_difference = 0.0, fast_ms = 0.0, reference_ms = 0.0, interacting_reference_ms = 0.0;
  for (const comparison& c : plans) {
    fast_ms += c.fast_ms;
    reference_ms += c.reference_ms;
    if (c.relevant > 0) interacting_reference_ms += c.reference_ms;
    if (!c.compared) continue;  // not reached: compare() throws when it cannot compare
    ++compared;
    columns_only += c.columns_only ? 1 : 0;
    interacting += c.relevant > 0 ? 1 : 0;
    several += c.relevant > 1 ? 1 : 0;
    if (c.relevant > 0) worst.push_back(c.worst.value);
    if (largest == nullptr || c.worst.value > largest->worst.value) largest = &c;
    over += c.worst.value > o.bound ? 1 : 0;
    largest_room_difference = std::max(largest_room_difference, c.selected_room_difference);
    // τ̄ is judged by the map column's rooms, which decide it alone with one relevant obstacle; with
    // several the selected room and family are.
    // A plan compared by its columns alone has no selection to judge (its margins are 0).
    if (c.relevant == 1 && c.forecast_margin > o.bound) {
      ++forecast_judged;
      forecast_disagreements += c.fast_forecast != c.reference_forecast ? 1 : 0;
    }
    // Spec §11: the picks may differ where the two candidates are within the bound. With one
    // relevant obstacle, where the reference's families at its τ̄ differ by more, a fast pick of the
    // other family at the same τ̄ lies that far below; at another τ̄ (allowed when the best τ leads
    // by less than the bound) it is judged by the reference's index of the fast planner's pick.
    if (c.relevant > 0 && c.family_margin > o.bound) {
      ++family_judged;
      const bool pick_too_low = c.relevant > 1 || c.pick_shortfall > o.bound;
      family_disagreements += c.fast_family != c.reference_family && pick_too_low ? 1 : 0;
    }
    // The whole pick at once, with one relevant obstacle: both checks above in one, and also a
    // family that is worse at another τ̄.
    if (c.relevant == 1 && !c.columns_only) {
      ++picks_judged;
      picks_below += c.pick_shortfall > o.bound ? 1 : 0;
    }
  }
  std::sort(worst.begin(), worst.end());
  const auto count = static_cast<double>(std::max<std::size_t>(plans.size(), 1));
  const std::string grid_note = o.resolution ? "; every planning vehicle at " +
                                                   std::to_string(o.resolution->accelerations) + "x" +
                                                   std::to_string(o.resolution->curvatures)
                                             : "";
  std::printf("%s: %zu plans%s%s (every %zu), %zu compared, %zu with a relevant obstacle, %zu with several; "
              "reference %zux%zu (%zux1 without steering), proof %g s%s\n",
              o.scenario.c_str(), plans.size(), o.agent.empty() ? "" : " of ", o.agent.c_str(), o.every, compared,
              interacting, several, o.reference.sampling.accelerations, o.reference.sampling.curvatures,
              o.reference.one_dimensional_accelerations, o.reference.proof_resolution, grid_note.c_str());
  if (largest != nullptr) {
    std::printf("map: max |dMI| %.4f (%s at %.2f s, tau %.3f s, %s); over the plans with a relevant obstacle: "
                "median %.4f, p99 %.4f; plans over %g: %zu\n",
                largest->worst.value, largest->agent.c_str(), largest->time, largest->worst_tau,
                name_of(largest->worst.which).c_str(), quantile(worst, 0.5), quantile(worst, 0.99), o.bound, over);
  }
  std::printf("selection: tau disagreements %zu of %zu plans with one relevant obstacle whose best tau leads by > %g; "
              "family disagreements %zu of %zu plans whose selected family leads by > %g; picks more than %g below "
              "the reference's in its own indices %zu of %zu plans with one relevant obstacle; largest |d selected "
              "room| %.4f\n",
              forecast_disagreements, forecast_judged, o.bound, family_disagreements, family_judged, o.bound, o.bound,
              picks_below, picks_judged, largest_room_difference);
  std::printf("compared by their map columns alone (the reference's exhaustive search over several obstacles too "
              "large; no selection judged): %zu\n",
              columns_only);
  std::printf("time a plan: fast %.3f ms, reference %.1f ms (%.1f ms with a relevant obstacle)\n", fast_ms / count,
              reference_ms / count,
              interacting > 0 ? interacting_reference_ms / static_cast<double>(interacting) : 0.0);
  if (!o.csv.empty()) {
    std::ofstream file(o.csv);
    file << "t_s,agent,relevant,compared,columns_only,max_dmi,at_tau_s,at_family,fast_tau_s,reference_tau_s,fast_family,"
            "reference_family,tau_margin,family_margin,selected_room_difference,pick_shortfall\n";
    for (const comparison& c : plans) {
      char row[512];
      std::snprintf(row, sizeof row, "%.2f,%s,%zu,%d,%d,%.6f,%.3f,%s,%.3f,%.3f,%s,%s,%.6f,%.6f,%.6f,%.6f\n", c.time,
                    c.agent.c_str(), c.relevant, c.compared ? 1 : 0, c.columns_only ? 1 : 0, c.worst.value, c.worst_tau,
                    name_of(c.worst.which).c_str(), c.fast_tau, c.reference_tau, name_of(c.fast_family).c_str(),
                    name_of(c.reference_family).c_str(), c.forecast_margin, c.family_margin,
                    c.selected_room_difference, c.pick_shortfall);
      file << row;
    }
    if (!file) throw std::runtime_error("--csv " + o.csv + ": cannot write the file");
  }
  const bool broken = over > 0 || forecast_disagreements > 0 || family_disagreements > 0 || picks_below > 0;
  return o.check && broken ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace cli = mm::tool_cli;
  options o;
  CLI::App app{"Runs a scenario and plans every planning input of its planning vehicles (or of --agent) with both\n"
               "the fast and the reference planner (spec §11): the largest |MI_fast - MI_reference| over forecast\n"
               "times and families, and whether the forecast time and the family agree where the reference's best\n"
               "candidate leads by more than the bound; with one relevant obstacle, whether the fast planner's pick\n"
               "lies within the bound below the reference's in the reference's own indices.\n",
               "maneuvermap_scenario_accuracy"};
  mm::capture::add_scenario_options(app, o);
  cli::add_whole(app, "--every", o.every, 1, cli::unbounded, "Compare every K-th plan only (>= 1)", "K");
  cli::add_real(app, "--from", o.from, cli::real_bound::non_negative, "s",
                "Compare only plans from this time on [s] (>= 0)", "T");
  cli::add_real(app, "--until", o.until, cli::real_bound::non_negative, "s",
                "Compare only plans up to this time [s] (>= 0)", "T");
  cli::add_whole(app, "--jobs", o.jobs, 1, 256, "Reference plans at a time (1 to 256)", "J");
  cli::add_whole(app, "--ref-accelerations", o.reference.sampling.accelerations, 2, 2001,
                 "Reference grid: accelerations per family (2 to 2001)", "A");
  cli::add_whole(app, "--ref-curvatures", o.reference.sampling.curvatures, 1, 2001,
                 "Reference grid: curvatures (1 to 2001)", "C");
  cli::add_whole(app, "--ref-accelerations-1d", o.reference.one_dimensional_accelerations, 2, 2001,
                 "Reference grid without steering (the one-dimensional case): accelerations per family (2 to 2001)", "A");
  cli::add_real(app, "--ref-proof-resolution", o.reference.proof_resolution, cli::real_bound::positive, "s",
                "Time resolution of the reference's continuous-time collision proof [s] (> 0)", "S");
  cli::add_real(app, "--bound", o.bound, cli::real_bound::positive, "",
                "The accuracy bound of spec §11 (> 0)", "B");
  app.add_option_function<std::string>(
      "--resolution",
      [&o](const std::string& text) { o.resolution = cli::parse_grid(text); },  // checked by grid_of_samples
      "Plan every planning vehicle at this grid instead of its own: A accelerations per family (2 to 2001) x C "
      "curvatures (1 to 2001)")
      ->check(cli::grid_of_samples())
      ->type_name("AxC");
  app.add_flag("--check", o.check, "Exit with code 1 when a plan breaks the bound");
  app.add_option("--csv", o.csv, "Write one row per compared plan to this file")->type_name("FILE.csv");
  return cli::run(app, argc, argv, [&] {
    if (o.until && *o.until < o.from) throw CLI::ValidationError("--until", "must not be before --from");
    return measure(o);
  });
}
