#pragma once

// Parameter sweeps (`maneuvermap sweep`): a grid of runs of one scenario over parameter values,
// forecast policies and seeded repetitions, run in parallel, written as runs.csv and aggregated
// per cell as table.csv and table.md (docs/outputs.md, "Sweeps").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mm/forecast_policy.hpp"
#include "mm/sim/metrics.hpp"

namespace mm::cli {

/// The format a sweep file declares (the value of its `format` key).
inline constexpr std::string_view sweep_format_version = "maneuvermap-sweep/1";

/// A sweep file compiled into the binary from `sweeps/NAME.yaml`.
struct builtin_sweep {
  std::string_view name;  ///< the file's stem, e.g. `table1`
  std::string_view text;  ///< the file's bytes
};

/// Every built-in sweep, sorted by name.
std::span<const builtin_sweep> builtin_sweeps();

/// The built-in sweep called `name`, or null.
const builtin_sweep* find_builtin_sweep(std::string_view name);

/// One swept parameter of the scenario and its values, in file order.
struct sweep_parameter {
  std::string name;            ///< as in the scenario's `parameters:` (with its unit suffix)
  std::vector<double> values;  ///< at least one, no duplicates
};

/// A sweep file, parsed and checked against its scenario.
struct sweep_spec {
  std::string name;         ///< default output directory `out/<name>`
  std::string description;
  std::string source;       ///< where the sweep came from: the file name or `builtin:NAME`
  /// The scenario as written in the file: a built-in name, or a path relative to the sweep file.
  std::string scenario;
  /// What `maneuvermap run` takes to load the same scenario: the built-in name, or the path
  /// resolved against the sweep file's directory.
  std::string scenario_argument;
  std::string scenario_text;    ///< its bytes, read once when the sweep is loaded
  std::string scenario_source;  ///< `builtin:NAME` or the resolved path, for messages
  std::string agent;            ///< the planning vehicle whose metrics runs.csv reports
  std::vector<sweep_parameter> parameters;  ///< outermost first
  /// The policies to run, in order; empty: the scenario's own (no `--policy`).
  std::vector<mm::forecast_policy> policies;
  std::string scenario_policy;  ///< the agent's own policy name (`adj`, `const:1`), used when `policies` is empty
  std::size_t repetitions = 1;
  std::uint64_t base_seed = 0;  ///< repetition r runs with seed base_seed + r
  bool keep_runs = false;       ///< write every run's own output directory under runs/
  /// `--on-roads`: every run plans on the scenario's roads and roundabout lanes
  /// (`scenario_file::load_options::on_roads`).
  bool on_roads = false;
};

/// Parses sweep YAML `text`. `source` names it in messages, `base_dir` resolves a relative
/// scenario path. Loads the scenario once with its defaults to check the parameter names and the
/// agent. Throws scenario_file::scenario_error (`FILE:LINE:COLUMN: FIELD = VALUE: expected WHAT`)
/// for any problem of the sweep file, or that of its scenario.
sweep_spec load_sweep_text(std::string_view text, const std::string& source, const std::filesystem::path& base_dir);

/// A built-in sweep by name, or a sweep file (an argument containing '/' or ending in `.yaml` or
/// `.yml` is a file; otherwise a built-in name if there is one, else a file).
sweep_spec load_sweep(std::string_view file_or_builtin);

/// The most runs a sweep may have in all (parameter values × policies × repetitions).
inline constexpr std::size_t largest_run_count = 1'000'000;

/// Replaces the repetitions of `spec` (`--repetitions N`); throws `std::invalid_argument`, naming the
/// runs it would make, when N is 0 or the sweep would have more than `largest_run_count` runs.
void set_repetitions(sweep_spec& spec, std::size_t repetitions);

/// One run of the grid.
struct sweep_run {
  std::size_t index = 0;             ///< position in grid order (= row of runs.csv)
  std::vector<double> values;        ///< one per sweep_spec::parameters
  std::size_t policy_index = 0;      ///< into sweep_spec::policies (0 when it is empty)
  std::string policy;                ///< `adj`, `const:0.5`, or the scenario's own
  std::size_t repetition = 0;
  std::uint64_t seed = 0;
  std::string run_dir;               ///< directory name under runs/ when runs are kept
};

/// Every run in grid order: parameters (the first outermost, values in file order), then
/// policies, then repetitions (innermost).
std::vector<sweep_run> expand(const sweep_spec& spec);

/// The `maneuvermap run` command line that reproduces `run` alone.
std::string run_command_line(const sweep_spec& spec, const sweep_run& run);

/// What one run gave.
struct sweep_result {
  sweep_run run;
  std::optional<mm::sim::run_metrics> metrics;  ///< of sweep_spec::agent; none when it failed
  std::string error;                            ///< why it failed; "" when fine
};

struct sweep_settings {
  std::filesystem::path out_dir;     ///< created if missing; files are overwritten
  unsigned jobs = 0;                 ///< parallel runs; 0: the hardware concurrency
  std::ostream* progress = nullptr;  ///< a terminal to draw a progress bar on, or null
};

struct sweep_outcome {
  std::vector<sweep_result> results;  ///< in grid order
  std::size_t failed = 0;
  std::vector<std::string> files;     ///< the files written (not those of kept runs)
};

/// Runs every run of `spec` on `settings.jobs` threads (each run loads and simulates its own
/// scenario; nothing is shared) and writes runs.csv, table.csv, table.md and sweep.json into
/// `settings.out_dir`, plus runs/<run_dir>/ for each run when runs are kept. The files do not
/// depend on the number of jobs. A failing run is recorded with its error and does not stop the
/// others. Throws std::runtime_error when an output file cannot be written.
sweep_outcome run_sweep(const sweep_spec& spec, const sweep_settings& settings);

/// runs.csv: the parameters, `policy,rep,seed`, the metrics, `error`.
std::string runs_csv(const sweep_spec& spec, std::span<const sweep_result> results);
/// table.csv: per cell (parameters × policy), counts, means and standard deviations.
std::string table_csv(const sweep_spec& spec, std::span<const sweep_result> results);
/// table.md: the same cells as a Markdown table, `mean ± sd`.
std::string table_markdown(const sweep_spec& spec, std::span<const sweep_result> results);

}  // namespace mm::cli
