#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/planner.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/metrics.hpp"

namespace mm::cli {

/// Bad input to a command that is not a scenario-file problem (unknown agent, time beyond the
/// run, τ off the grid): exit code 2, like `scenario_file::scenario_error`.
class input_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Options of `maneuvermap run` once the scenario is loaded.
struct run_settings {
  std::filesystem::path out_dir;  ///< created if missing; the five files are overwritten
  bool measure_cpu_time = false;  ///< `--timing`: fill cpu_us and the CPU fields of summary.json
  std::size_t jobs = 1;  ///< `--jobs`: threads planning the vehicles of a step (outputs do not depend on it)
  std::ostream* progress = nullptr;  ///< where to show progress (a terminal), or null
  /// `--commonroad FILE.xml`: also the run as a CommonRoad recording (`commonroad_recording`), its
  /// states every `commonroad_step` [s] (a whole multiple of the run's time step); empty: none.
  std::filesystem::path commonroad_file;
  double commonroad_step = 0.1;
};

/// What a run produced.
struct run_outcome {
  std::vector<mm::sim::run_metrics> metrics;  ///< per planning vehicle, in id order
  double end_time = 0.0;                      ///< [s]
  std::vector<std::string> files;             ///< the files written, in order
};

/// Runs `loaded` and writes trajectories.csv, map.csv, decisions.csv, summary.json and
/// scene.json into `settings.out_dir` (docs/outputs.md). Without CPU timing the files are a
/// function of the scenario, its parameters and its seed alone (byte-identical on every run).
/// Throws std::invalid_argument (`mm::sim::validation_error`) before writing anything when the
/// scenario is invalid, input_error (also before) when `commonroad_step` is not a whole multiple
/// of its time step, std::runtime_error when a file cannot be written.
run_outcome run_scenario(const scenario_file::loaded_scenario& loaded, const run_settings& settings);

/// The §12 metrics as a small aligned table, one row per planning vehicle (`maneuvermap run`).
std::string metrics_table(const std::vector<mm::sim::run_metrics>& metrics, bool with_cpu);

/// The common forecast policy of the planning vehicles (`adj`, `const:1`), `mixed`, or `none`.
std::string scenario_policy(const mm::sim::scenario& s);

/// One sampled maneuver of a snapshot under one forecast time.
struct snapshot_row {
  double forecast_time = 0.0;  ///< τ_i [s]
  mm::family fam = mm::family::brake;
  mm::maneuver u;
  vec2 end_point;              ///< displacement at T_h, world frame [m]
  double area_weight = 0.0;    ///< [m²]
  bool safe = false;           ///< safe with every obstacle forecast with τ_i
  /// Safe under the forecast times the decision used (`sample_snapshot::safe_selected`): each
  /// obstacle at its own, or under the robust policy each at every non-excluded one. The same in
  /// every row of a sample.
  bool selected = false;
};

/// A re-plan of one planning vehicle with the samples recorded (`maneuvermap snapshot`).
struct snapshot {
  std::string agent;            ///< the re-planned planning vehicle
  std::vector<std::string> obstacle_names;  ///< the agent behind each of input.obstacles
  double time = 0.0;            ///< the simulation time at which it was taken [s]
  mm::plan_input input;         ///< what the vehicle planned on (config.record_samples = true)
  mm::plan_result result;       ///< with `samples`
  std::vector<snapshot_row> rows;  ///< every sample under every τ_i, or under `tau` only
};

/// Runs `loaded` to the first step at or after `time` [s], then re-plans planning vehicle
/// `agent` with `record_samples` (`simulation::planning_input`). Rows for every τ_i, or only for
/// `tau` when given (which must lie on the forecast grid). Throws input_error when the agent is
/// unknown or not a planning vehicle, when `time` is negative or beyond the duration, when the run
/// ends before `time`, or when the vehicle is not driving then.
snapshot take_snapshot(const scenario_file::loaded_scenario& loaded, const std::string& agent, double time,
                       std::optional<double> tau);

/// Writes `rows` as CSV `tau,family,accel,curvature,end_x,end_y,area_weight,safe`.
void write_snapshot_csv(std::ostream& out, const snapshot& shot);

/// Writes what the CSV's rows do not repeat, as one JSON object `maneuvermap-snapshot/1`: the
/// time, the ego's pose, speed and footprint, T_h, τ̄, the family, mode and TTC, the nominal and
/// the chosen maneuver with their displacements, and each obstacle's estimated motion and its
/// forecast at its forecast time (docs/outputs.md). `loaded` names the scenario, policy and seed.
void write_snapshot_json(std::ostream& out, const snapshot& shot, const scenario_file::loaded_scenario& loaded);

/// Where `maneuvermap snapshot --out FILE.csv` writes the JSON: FILE.json.
std::filesystem::path snapshot_json_path(const std::filesystem::path& csv);

/// A finite value with 6 (or `decimals`, 0 to 17) decimals, correctly rounded ("-0.000000" written
/// as "0.000000"); "" when not finite.
std::string fixed(double value, int decimals = 6);

}  // namespace mm::cli
