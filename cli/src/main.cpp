// `maneuvermap`: runs scenario files and writes what they produce (docs/outputs.md).
// Exit codes: 0 success, 2 bad input (scenario file, option value, agent, time), 1 internal error.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <numeric>
#include <thread>

#include "mm/cli/commands.hpp"
#include "mm/cli/measure.hpp"
#include "mm/cli/replay.hpp"
#include "mm/cli/plot.hpp"
#include "mm/cli/sweep.hpp"
#include "mm/commonroad/reader.hpp"
#include "mm/planner.hpp"
#include "mm/scenario_file/builtin.hpp"
#include "mm/scenario_file/writer.hpp"
#include "mm/sim/memory.hpp"
#include "output_files.hpp"

namespace {

namespace sf = mm::scenario_file;

constexpr int exit_ok = 0;
constexpr int exit_internal = 1;
constexpr int exit_bad_input = 2;

/// An option's check: an integer from `lo` to `hi`; CLI11's own says "Value abc not in range".
CLI::Validator integer_in(std::uint64_t lo, std::uint64_t hi, std::string what = "an integer") {
  return CLI::Validator(
      [=](std::string& text) {
        std::uint64_t value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (!text.empty() && ec == std::errc() && end == text.data() + text.size() && value >= lo && value <= hi) return std::string();
        return fmt::format("expected {} from {} to {}, got {}", what, lo, hi, text);
      },
      "");
}

/// An option's check: a number in `unit` from `lo` to `hi`; without bounds, any number (the command
/// checks its range, e.g. a time within the run), where CLI11's own says "Could not convert".
CLI::Validator number_in(std::string_view unit, double lo = -std::numeric_limits<double>::infinity(),
                         double hi = std::numeric_limits<double>::infinity()) {
  return CLI::Validator(
      [=](std::string& text) {
        double value = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool number = !text.empty() && ec == std::errc() && end == text.data() + text.size();
        const bool bounded = std::isfinite(lo) || std::isfinite(hi);
        if (number && (!bounded || (value >= lo && value <= hi))) return std::string();
        if (!bounded) return fmt::format("expected a number of {}, got {}", unit, text);
        return fmt::format("expected a number of {} from {} to {}, got {}", unit, lo, hi, text);
      },
      "");
}

/// Options shared by the commands that load a scenario.
struct scenario_options {
  std::string file;
  std::vector<std::string> overrides;
  std::string policy;
  std::optional<std::uint64_t> seed;
  bool on_roads = false;
};

void add_scenario_options(CLI::App& command, scenario_options& o, bool with_policy) {
  command.add_option("FILE", o.file, "Scenario file, or the name of a built-in scenario (maneuvermap list)")->required();
  command.add_option("--set", o.overrides, "Override a parameter of the scenario: NAME=VALUE (repeatable)")
      ->type_name("NAME=VALUE");
  command.add_flag("--on-roads", o.on_roads,
                   "Plan on the road: the scenario's roads and its roundabout's 3.5 m lanes are the drivable area "
                   "(spec §5's road constraint; as drivable_area: {roads: true, roundabout: true})");
  if (with_policy) {
    command.add_option("--policy", o.policy, "Forecast policy of every planning vehicle: adj, const:SECONDS or robust")
        ->type_name("adj|const:SECONDS|robust");
    command.add_option("--seed", o.seed, "Seed of the sensor noise (replaces the scenario's)")
        ->check(CLI::Validator(
            [](std::string& text) {
              const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
                return c >= '0' && c <= '9';
              });
              return digits ? std::string() : "expected an integer from 0 to 18446744073709551615, got " + text;
            },
            "SEED"));
  }
}

/// The value of `--policy`: `adj`, `const:SECONDS` or `robust`; input_error for anything else.
mm::forecast_policy policy_option(const std::string& text) {
  const std::optional<mm::forecast_policy> policy = sf::parse_policy(text);
  if (!policy) {
    throw mm::cli::input_error("--policy " + text + ": expected " + std::string(sf::policy_forms) + ", e.g. const:1.0");
  }
  return *policy;
}

/// `--policy` for a planner of configuration `config` (measure, replay: the default one): its
/// constant forecast time must lie on that configuration's forecast grid.
mm::forecast_policy policy_option(const std::string& text, mm::planner_config config) {
  config.policy = policy_option(text);
  mm::plan_input probe;
  probe.config = config;
  if (const std::optional<std::string> error = mm::validation_error(probe)) {
    throw mm::cli::input_error("--policy " + text + ": " + *error);
  }
  return config.policy;
}

sf::loaded_scenario load(const scenario_options& o) {
  sf::load_options options;
  for (const std::string& text : o.overrides) {
    auto parsed = sf::parse_override(text);
    if (!parsed) throw mm::cli::input_error("--set " + text + ": expected NAME=VALUE with a finite number VALUE");
    options.overrides.push_back(*parsed);
  }
  if (!o.policy.empty()) options.policy = policy_option(o.policy);
  options.seed = o.seed;
  options.on_roads = o.on_roads;
  return sf::load(o.file, options);
}

std::string first_line(std::string_view text) {
  const std::size_t end = text.find('\n');
  return std::string(end == std::string_view::npos ? text : text.substr(0, end));
}

int list_command() {
  std::size_t width = 0;
  for (const sf::builtin_scenario& b : sf::builtin_scenarios()) width = std::max(width, b.name.size());
  for (const mm::cli::builtin_sweep& b : mm::cli::builtin_sweeps()) width = std::max(width, b.name.size());
  std::cout << "built-in scenarios (maneuvermap run NAME):\n";
  for (const sf::builtin_scenario& b : sf::builtin_scenarios()) {
    const sf::loaded_scenario loaded = sf::load_text(b.text, "builtin:" + std::string(b.name));
    std::cout << fmt::format("  {:<{}}  {}\n", b.name, width, first_line(loaded.scenario.description));
  }
  std::cout << "\nbuilt-in sweeps (maneuvermap sweep NAME):\n";
  for (const mm::cli::builtin_sweep& b : mm::cli::builtin_sweeps()) {
    const mm::cli::sweep_spec spec = mm::cli::load_sweep_text(b.text, "builtin:" + std::string(b.name), ".");
    std::cout << fmt::format("  {:<{}}  {}\n", b.name, width, first_line(spec.description));
  }
  return exit_ok;
}

int validate_command(const scenario_options& o) {
  const sf::loaded_scenario loaded = load(o);
  const mm::sim::scenario& s = loaded.scenario;
  std::cout << fmt::format("{}: valid ({}): {} planning, {} scripted, {} pedestrians, {} static; {} s at {:g} s steps\n",
                           loaded.source, s.name, s.planning_vehicles.size(), s.scripted_vehicles.size(),
                           s.pedestrians.size(), s.static_obstacles.size(), mm::cli::fixed(s.duration, 2), s.time_step);
  for (const sf::parameter& p : loaded.parameters) std::cout << fmt::format("  parameter {} = {}\n", p.name, p.value);
  for (const sf::meeting_report& m : loaded.meetings) {
    std::cout << fmt::format("  meet {} and {}: {} m ({} s) and {} m ({} s), lag {} s: start at {} s and {} s\n", m.first,
                             m.second, mm::cli::fixed(m.first_distance, 3), mm::cli::fixed(m.first_travel, 3),
                             mm::cli::fixed(m.second_distance, 3), mm::cli::fixed(m.second_travel, 3),
                             mm::cli::fixed(m.lag, 3), mm::cli::fixed(m.first_start, 3), mm::cli::fixed(m.second_start, 3));
  }
  return exit_ok;
}

/// `scenario_text(s)` to `file`, or to standard output for "" or "-"; input_error when no file
/// can state `s` (exit 2), runtime_error when the file cannot be written (exit 1).
void write_scenario(const sf::loaded_scenario& s, const std::string& file) {
  std::string text;
  try {
    text = sf::scenario_text(s);
  } catch (const std::invalid_argument& e) {
    throw mm::cli::input_error(e.what());
  }
  if (file.empty() || file == "-") {
    std::cout << text;
    return;
  }
  mm::cli::output::write_text(file, text);
}

int resolve_command(const scenario_options& o, const std::string& out) {
  write_scenario(load(o), out);
  return exit_ok;
}

/// `--plots`: the figures of `dir` into `dir` (failures are reported as by `maneuvermap plot`).
void plot_into(const std::filesystem::path& dir) { mm::cli::draw_plots(dir, {}); }

int run_command(const scenario_options& o, const std::string& out, bool timing, bool plots, std::size_t jobs,
                const std::string& commonroad, double commonroad_step) {
  const sf::loaded_scenario loaded = load(o);
  mm::cli::run_settings settings;
  settings.commonroad_file = commonroad;
  settings.commonroad_step = commonroad_step;
  settings.out_dir = out.empty() ? std::filesystem::path("out") / loaded.scenario.name : std::filesystem::path(out);
  settings.measure_cpu_time = timing;
  // 0: every core, as `sweep` does (the outputs do not depend on it).
  settings.jobs = jobs != 0 ? jobs : std::max(1U, std::thread::hardware_concurrency());
  settings.progress = isatty(STDERR_FILENO) ? &std::cerr : nullptr;
  const mm::cli::run_outcome outcome = mm::cli::run_scenario(loaded, settings);
  std::cout << fmt::format("{}: policy {}, seed {}, ended at t = {} s\n", loaded.scenario.name,
                           mm::cli::scenario_policy(loaded.scenario), loaded.scenario.seed,
                           mm::cli::fixed(outcome.end_time, 2));
  std::cout << mm::cli::metrics_table(outcome.metrics, timing);
  std::cout << "written to " << settings.out_dir.string() << "/\n";
  if (plots) plot_into(settings.out_dir);
  return exit_ok;
}

struct sweep_options {
  std::string file;
  unsigned jobs = 0;
  std::string out;
  bool plots = false;
  bool keep_runs = false;
  bool on_roads = false;
  std::optional<std::size_t> repetitions;
};

int sweep_command(const sweep_options& o) {
  mm::cli::sweep_spec spec = mm::cli::load_sweep(o.file);
  if (o.keep_runs) spec.keep_runs = true;
  if (o.on_roads) {
    // Checked once before any run: a scenario without roads fails here, not in every run.
    sf::load_options check;
    check.on_roads = true;
    (void)sf::load_text(spec.scenario_text, spec.scenario_source, check);
    spec.on_roads = true;
  }
  if (o.repetitions) {
    try {
      mm::cli::set_repetitions(spec, *o.repetitions);
    } catch (const std::invalid_argument& e) {
      throw mm::cli::input_error(std::string("--") + e.what());
    }
  }
  mm::cli::sweep_settings settings;
  settings.out_dir = o.out.empty() ? std::filesystem::path("out") / spec.name : std::filesystem::path(o.out);
  settings.jobs = o.jobs;
  settings.progress = isatty(STDERR_FILENO) ? &std::cerr : nullptr;
  const auto started = std::chrono::steady_clock::now();
  const mm::cli::sweep_outcome outcome = mm::cli::run_sweep(spec, settings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::cout << mm::cli::table_markdown(spec, outcome.results) << "\n";
  for (const mm::cli::sweep_result& r : outcome.results) {
    if (r.error.empty()) continue;
    std::cerr << fmt::format("maneuvermap: run {} failed: {}\n  rerun it alone: {}\n", r.run.index, r.error,
                             mm::cli::run_command_line(spec, r.run));
  }
  std::cout << fmt::format("{}: {} runs, {} failed, in {} s; written to {}/\n", spec.name, outcome.results.size(),
                           outcome.failed, mm::cli::fixed(seconds, 1), settings.out_dir.string());
  if (o.plots) plot_into(settings.out_dir);
  return outcome.failed == 0 ? exit_ok : exit_internal;
}

int plot_command(const std::string& target, const std::string& out) {
  std::error_code ec;
  if (!std::filesystem::exists(target, ec)) throw mm::cli::input_error("plot: " + target + ": no such file or directory");
  mm::cli::draw_plots(target, out);
  return exit_ok;
}

int snapshot_command(const scenario_options& o, double time, const std::string& agent, std::optional<double> tau,
                     const std::string& out) {
  const sf::loaded_scenario loaded = load(o);
  const mm::cli::snapshot shot = mm::cli::take_snapshot(loaded, agent, time, tau);
  if (out.empty()) {
    mm::cli::write_snapshot_csv(std::cout, shot);
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return exit_ok;
  }
  std::ofstream file(out, std::ios::binary);
  if (!file) throw std::runtime_error("cannot write " + out);
  mm::cli::write_snapshot_csv(file, shot);
  file.close();
  if (!file) throw std::runtime_error("cannot write " + out);
  const std::filesystem::path json_file = mm::cli::snapshot_json_path(out);
  std::ofstream sidecar(json_file, std::ios::binary);
  mm::cli::write_snapshot_json(sidecar, shot, loaded);
  sidecar.close();
  if (!sidecar) throw std::runtime_error("cannot write " + json_file.string());
  return exit_ok;
}

struct measure_command_options {
  std::vector<std::string> files;
  std::vector<std::string> agents;
  std::string policy;
  std::string out;
  bool plots = false;
  bool on_lanelets = false;
  std::size_t jobs = 0;
};

/// `--agent` values: road-user ids, or `all` alone.
void parse_agents(const std::vector<std::string>& texts, mm::cli::measure_settings& settings) {
  for (const std::string& text : texts) {
    if (text == "all") {
      settings.every_road_user = true;
      continue;
    }
    std::uint32_t id = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
    if (ec != std::errc() || end != text.data() + text.size() || id == 0) {
      throw mm::cli::input_error("--agent " + text + ": expected the id of a road user of the file (a positive integer) or all");
    }
    if (std::find(settings.agents.begin(), settings.agents.end(), id) != settings.agents.end()) {
      throw mm::cli::input_error("--agent " + text + ": given twice; each road user is measured once");
    }
    settings.agents.push_back(id);
  }
  if (settings.every_road_user && !settings.agents.empty()) {
    throw mm::cli::input_error("--agent all: measures every road user; give it alone, not with ids");
  }
}

/// `maneuvermap measure FILE...`: one file into --out (default out/<name>); several, each into
/// <out>/<name>/ (default out/measure) and one row per measured road user into
/// <out>/measurements.csv.
int measure_command(const measure_command_options& o) {
  mm::cli::measure_settings settings;
  parse_agents(o.agents, settings);
  if (!o.policy.empty()) settings.policy = policy_option(o.policy, mm::planner_config{});
  settings.jobs = o.jobs != 0 ? o.jobs : std::max(1U, std::thread::hardware_concurrency());
  settings.on_lanelets = o.on_lanelets;
  settings.progress = isatty(STDERR_FILENO) ? &std::cerr : nullptr;
  if (o.files.size() > 1 && !settings.agents.empty()) {
    throw mm::cli::input_error("--agent " + std::to_string(settings.agents.front()) +
                               ": an id names a road user of one file; with several files give --agent all, or no "
                               "--agent for each file's recorded ego");
  }
  const std::filesystem::path out = o.out.empty() ? std::filesystem::path("out") / "measure" : std::filesystem::path(o.out);
  std::vector<mm::cli::measure_request> requests;
  for (const std::string& file : o.files) {
    const std::string name = std::filesystem::path(file).stem().string();
    const auto same = std::find_if(requests.begin(), requests.end(), [&](const auto& r) { return r.name == name; });
    if (same != requests.end()) {
      throw mm::cli::input_error(fmt::format("{} and {}: two files named {}; each file's outputs go to a folder of its name",
                                             same->file, file, name));
    }
    const std::filesystem::path dir = o.files.size() == 1 ? (o.out.empty() ? std::filesystem::path("out") / name : out)
                                                          : out / name;
    requests.push_back({file, name, dir});
  }
  const std::vector<mm::cli::measured_file> measured = mm::cli::measure_files(requests, settings);
  for (std::size_t k = 0; k < measured.size(); ++k) {
    const mm::cli::measured_file& f = measured[k];
    std::cout << fmt::format("{}: CommonRoad {}, {} road users and obstacles, time step {} s; policy {}\n", f.name,
                             f.commonroad_version, f.obstacles, mm::cli::fixed(f.time_step, 3),
                             sf::policy_name(settings.policy));
    std::cout << mm::cli::measurement_table(f);
    std::cout << "written to " << requests[k].out_dir.string() << "/\n";
    if (o.plots) plot_into(requests[k].out_dir);
  }
  if (o.files.size() == 1) return exit_ok;
  mm::cli::output::write_text(out / "measurements.csv", mm::cli::measurements_csv(measured));
  std::cout << fmt::format("{} files, {} road users: {}\n", measured.size(),
                           std::accumulate(measured.begin(), measured.end(), std::size_t{0},
                                           [](std::size_t n, const mm::cli::measured_file& f) {
                                             return n + f.road_users.size();
                                           }),
                           (out / "measurements.csv").string());
  return exit_ok;
}

struct replay_command_options {
  std::string file;
  std::optional<std::uint32_t> agent;
  std::string policy;
  std::optional<double> desired_speed_kmh;
  bool no_avoidance = false;
  bool on_lanelets = false;
  bool reactive = false;
  std::string out;
  bool plots = false;
  std::string scenario_out;
};

int replay_command(const replay_command_options& o) {
  mm::commonroad::replay_options options;
  if (!o.policy.empty()) options.config.policy = policy_option(o.policy, options.config);
  if (o.desired_speed_kmh) options.desired_speed = *o.desired_speed_kmh / 3.6;
  options.avoidance = !o.no_avoidance;
  options.on_lanelets = o.on_lanelets;
  if (o.reactive) options.reactive = mm::commonroad::reactive_traffic();
  const mm::commonroad::scenario recording = mm::commonroad::read_scenario(o.file);
  const sf::loaded_scenario loaded = [&] {
    try {
      options.agent = o.agent ? *o.agent : mm::cli::default_replay_agent(recording);
      return mm::cli::replay_loaded(recording, options, o.file);
    } catch (const mm::cli::input_error& e) {
      throw mm::cli::input_error(o.file + ": " + e.what());
    } catch (const mm::commonroad::measure_error& e) {
      throw mm::commonroad::measure_error(o.file + ": " + e.what());
    }
  }();
  if (!o.scenario_out.empty()) write_scenario(loaded, o.scenario_out);
  const std::string name = std::filesystem::path(o.file).stem().string();
  mm::cli::run_settings settings;
  settings.out_dir = o.out.empty() ? std::filesystem::path("out") / (name + "-replay") : std::filesystem::path(o.out);
  settings.jobs = 1;
  settings.progress = isatty(STDERR_FILENO) ? &std::cerr : nullptr;
  const mm::cli::run_outcome outcome = mm::cli::run_scenario(loaded, settings);
  const mm::sim::planning_vehicle& ego = loaded.scenario.planning_vehicles.front();
  const std::string desired = ego.desired_speed_profile ? std::string("its recorded speeds")
                                                         : mm::cli::fixed(ego.desired_speed * 3.6, 1) + " km/h";
  std::cout << fmt::format("{}: road user {} driven by the planner ({}), desired speed {}, policy {}; "
                           "the others replayed{}; ended at t = {} s\n",
                           name, options.agent, options.avoidance ? "avoiding" : "without avoidance", desired,
                           sf::policy_name(options.config.policy),
                           options.reactive ? ", reacting (car following)" : "", mm::cli::fixed(outcome.end_time, 2));
  std::cout << mm::cli::metrics_table(outcome.metrics, false);
  std::cout << "written to " << settings.out_dir.string() << "/\n";
  if (o.plots) plot_into(settings.out_dir);
  return exit_ok;
}

}  // namespace

int main(int argc, char** argv) {
  mm::sim::retain_freed_memory();  // a sweep's runs reuse each other's freed buffers
  CLI::App app{"maneuvermap: collision-avoidance planning with Maneuverability Maps, and its traffic simulator"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "maneuvermap 0.1.0");

  CLI::App* list = app.add_subcommand("list", "List the built-in scenarios with a one-line description");

  scenario_options validate_options;
  CLI::App* validate = app.add_subcommand("validate", "Check a scenario file; exit 0 if valid, 2 if not");
  add_scenario_options(*validate, validate_options, false);

  scenario_options resolve_options;
  std::string resolve_out;
  CLI::App* resolve = app.add_subcommand(
      "resolve",
      "Write a scenario as the simulator runs it: every field given, SI units, parameters, defaults and meetings "
      "resolved; the file runs exactly as the scenario does");
  add_scenario_options(*resolve, resolve_options, true);
  resolve->add_option("--out,-o", resolve_out, "The file to write (default: standard output)")->type_name("FILE");

  scenario_options run_options;
  std::string run_out;
  bool timing = false;
  CLI::App* run = app.add_subcommand("run", "Run a scenario: print the run metrics and write the output files");
  add_scenario_options(*run, run_options, true);
  run->add_option("--out", run_out, "Output directory (default out/<scenario name>)")->type_name("DIR");
  run->add_flag("--timing", timing, "Measure the CPU time of each planning step (outputs are then not reproducible)");
  bool run_plots = false;
  std::size_t run_jobs = 0;
  run->add_option("--jobs,-j", run_jobs,
                  "Threads planning the vehicles of a step (outputs do not depend on it; default: the number of cores)")
      ->check(integer_in(1, 256))
      ->type_name("N");
  run->add_flag("--plots", run_plots, "Then draw the run's figures into its output directory (maneuvermap plot)");
  std::string run_commonroad;
  double run_commonroad_step = 0.1;
  run->add_option("--commonroad", run_commonroad,
                  "Also write the run as a CommonRoad recording (XML, 2020a), which maneuvermap measure reads")
      ->type_name("FILE.xml");
  run->add_option("--commonroad-step", run_commonroad_step,
                  "The recording's time step, a whole multiple of the run's (default 0.1 s)")
      ->check(number_in("s", 1e-6, 3600.0))
      ->type_name("SECONDS");

  sweep_options sweep_opts;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run a parameter sweep (grid of parameters x policies x seeded repetitions) in parallel; write runs.csv, table.csv, table.md");
  sweep->add_option("FILE", sweep_opts.file, "Sweep file, or the name of a built-in sweep (maneuvermap list)")->required();
  sweep->add_option("--jobs,-j", sweep_opts.jobs, "Runs in parallel (default: the number of cores)")
      ->check(integer_in(1, 256))
      ->type_name("N");
  sweep->add_option("--out", sweep_opts.out, "Output directory (default out/<sweep name>)")->type_name("DIR");
  sweep->add_flag("--keep-runs", sweep_opts.keep_runs, "Also write every run's own output directory under DIR/runs/");
  sweep->add_flag("--on-roads", sweep_opts.on_roads,
                  "Every run plans on the scenario's roads and roundabout lanes (as run --on-roads)");
  sweep->add_option("--repetitions", sweep_opts.repetitions, "Replace the sweep file's repetitions (e.g. 1 for a preview)")
      ->check(integer_in(1, 1000000))
      ->type_name("N");
  sweep->add_flag("--plots", sweep_opts.plots, "Then draw the sweep's figures into DIR (maneuvermap plot)");

  std::string plot_target;
  std::string plot_out;
  CLI::App* plot = app.add_subcommand(
      "plot", "Draw the figures (PNG and SVG) of a run directory, a sweep directory or a snapshot CSV with matplotlib");
  plot->add_option("TARGET", plot_target, "A run directory, a sweep directory or a snapshot CSV")->required()->type_name("RUN_OR_SWEEP_DIR");
  plot->add_option("--out", plot_out, "Where to write the figures (default: the directory itself, or the CSV's directory)")
      ->type_name("DIR");

  scenario_options snapshot_options;
  double snapshot_time = 0.0;
  std::string snapshot_agent;
  std::optional<double> snapshot_tau;
  std::string snapshot_out;
  CLI::App* snapshot = app.add_subcommand(
      "snapshot", "Run to a time, re-plan one planning vehicle and write its sampled maneuvers and their safety as CSV");
  add_scenario_options(*snapshot, snapshot_options, true);
  snapshot->add_option("--time", snapshot_time, "Simulation time to stop at [s]")
      ->required()
      ->check(number_in("seconds"))
      ->type_name("SECONDS");
  snapshot->add_option("--agent", snapshot_agent, "The planning vehicle to re-plan")->required()->type_name("NAME");
  snapshot->add_option("--tau", snapshot_tau, "Only this forecast time [s] (default: every one)")
      ->check(number_in("seconds"))
      ->type_name("SECONDS");
  snapshot->add_option("--out", snapshot_out, "CSV file to write (default: standard output)")->type_name("FILE.csv");

  measure_command_options measure_options;
  CLI::App* measure = app.add_subcommand(
      "measure", "Measure the room to maneuver of road users recorded in a CommonRoad file: their Maneuverability Maps");
  measure->add_option("FILE", measure_options.files,
                      "CommonRoad scenario files (XML, version 2018b or 2020a); several: each into a folder of its name, "
                      "and one row per measured road user into measurements.csv")
      ->required()
      ->type_name("FILE.xml...");
  measure->add_option("--agent", measure_options.agents,
                      "Road user to measure, by obstacle id (repeatable), or all (default: the recorded ego of the planning problem)")
      ->type_name("ID|all");
  measure->add_option("--policy", measure_options.policy, "Forecast policy: adj (default), const:SECONDS or robust")
      ->type_name("adj|const:SECONDS|robust");
  measure->add_option("--out", measure_options.out,
                      "Output directory (default out/<file name without .xml>; with several files out/measure)")
      ->type_name("DIR");
  measure->add_option("--jobs,-j", measure_options.jobs,
                      "Road users measured at a time (outputs do not depend on it; default: the number of cores)")
      ->check(integer_in(1, 256))
      ->type_name("N");
  measure->add_flag("--on-lanelets", measure_options.on_lanelets,
                    "Count only the room on the road: a maneuver whose footprint leaves the union of the file's "
                    "lanelets within T_h is unsafe (the road constraint of spec §5)");
  measure->add_flag("--plots", measure_options.plots, "Then draw the figures into the output directory (maneuvermap plot)");

  replay_command_options replay_options;
  CLI::App* replay = app.add_subcommand(
      "replay",
      "Drive one road user of a CommonRoad recording with the planner, the others replayed; write a run's files");
  replay->add_option("FILE", replay_options.file, "CommonRoad scenario file (XML, version 2018b or 2020a)")
      ->required()
      ->type_name("FILE.xml");
  replay->add_option("--agent", replay_options.agent,
                     "The road user to drive (default: the recorded ego of the file's planning problem)")
      ->check(integer_in(1, std::numeric_limits<std::uint32_t>::max(),
                         "the id of the one road user to drive (replay drives one; measure takes all), an integer"))
      ->type_name("ID");
  replay->add_option("--policy", replay_options.policy, "Forecast policy: adj (default), const:SECONDS or robust")
      ->type_name("adj|const:SECONDS|robust");
  replay->add_option("--desired-speed", replay_options.desired_speed_kmh,
                     "Its desired speed in km/h (default: its recorded speed at each moment)")
      ->check(number_in("km/h", 0.0, 360.0))
      ->type_name("KMH");
  replay->add_flag("--no-avoidance", replay_options.no_avoidance,
                   "Follow the recorded path without planning (the baseline)");
  replay->add_flag("--on-lanelets", replay_options.on_lanelets,
                   "Keep the planned road user on the union of the file's lanelets within T_h (the road constraint of "
                   "spec §5)");
  replay->add_flag("--reactive", replay_options.reactive,
                   "The other vehicles keep their distance to the driven road user, and to those it holds up, "
                   "ahead on their recorded paths, lagging behind their recordings where they must (car "
                   "following, docs/commonroad.md)");
  replay->add_option("--out", replay_options.out, "Output directory (default out/<file name>-replay)")
      ->type_name("DIR");
  replay->add_option("--write-scenario", replay_options.scenario_out,
                     "Also write the replay as a scenario file (maneuvermap resolve's form) that runs as it does")
      ->type_name("FILE.yaml");
  replay->add_flag("--plots", replay_options.plots, "Then draw the run's figures into its output directory");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "maneuvermap: " << e.what() << "\nRun with --help for more information.\n";
    return exit_bad_input;
  }

  try {
    if (list->parsed()) return list_command();
    if (validate->parsed()) return validate_command(validate_options);
    if (resolve->parsed()) return resolve_command(resolve_options, resolve_out);
    if (run->parsed()) {
      return run_command(run_options, run_out, timing, run_plots, run_jobs, run_commonroad, run_commonroad_step);
    }
    if (sweep->parsed()) return sweep_command(sweep_opts);
    if (plot->parsed()) return plot_command(plot_target, plot_out);
    if (snapshot->parsed()) return snapshot_command(snapshot_options, snapshot_time, snapshot_agent, snapshot_tau, snapshot_out);
    if (measure->parsed()) return measure_command(measure_options);
    if (replay->parsed()) return replay_command(replay_options);
  } catch (const sf::scenario_error& e) {
    std::cerr << "maneuvermap: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const mm::commonroad::read_error& e) {
    std::cerr << "maneuvermap: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const mm::commonroad::measure_error& e) {
    std::cerr << "maneuvermap: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const mm::cli::input_error& e) {
    std::cerr << "maneuvermap: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::cerr << "maneuvermap: error: " << e.what() << "\n";
    return exit_internal;
  }
  return exit_internal;
}
