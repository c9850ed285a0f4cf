// The built `maneuvermap` executable's sweep and plot commands: exit codes, messages, and figures
// drawn on a small run directory, a small sweep directory and a snapshot (non-empty PNG files).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli/support.hpp"

namespace {

using mm::cli::testing::read_file;
using mm::cli::testing::temp_dir;
using mm::cli::testing::write_file;

using result = mm::cli::testing::command_result;
using mm::cli::testing::contains;

/// Runs `ENV maneuvermap ARGS` (shell text) with its output captured.
result run(const std::string& args, const std::string& tag, const std::string& env = "") {
  const temp_dir dir("sweep_binary_" + tag);
  return mm::cli::testing::run_command(MANEUVERMAP_EXE, args, dir, env);
}

const std::string scenario = std::string(MM_TESTS_CLI_DIR) + "/data/small-crossing.yaml";

/// A sweep file of the small scenario: 2 cells × 2 repetitions of 1.5 s runs, plus `extra`.
std::string small_sweep(const std::string& parameters, const std::string& extra = "") {
  return "format: maneuvermap-sweep/1\nname: small\nscenario: " + scenario + "\nparameters:\n" + parameters +
         "  duration_s: 1.5\npolicies: [adj]\nrepetitions: 2\n" + extra;
}

/// Whether the plots can be drawn here: /usr/bin/python3 (or MM_PYTHON) imports matplotlib. In CI
/// (CI set) they must be: scripts/install-deps.sh installs python3-matplotlib.
bool matplotlib_available() {
  const char* python = std::getenv("MM_PYTHON");
  const std::string command = std::string(python != nullptr && *python != '\0' ? python : "/usr/bin/python3") +
                              " -c 'import matplotlib, numpy' >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

#define REQUIRE_MATPLOTLIB()                                                                          \
  do {                                                                                                \
    if (!matplotlib_available()) {                                                                    \
      if (std::getenv("CI") != nullptr) FAIL() << "matplotlib is missing in CI (scripts/install-deps.sh)"; \
      GTEST_SKIP() << "python3-matplotlib is not installed (scripts/install-deps.sh installs it)";      \
    }                                                                                                 \
  } while (false)

void expect_png(const std::filesystem::path& file) {
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const std::string bytes = read_file(file);
  EXPECT_GT(bytes.size(), 5000U) << file;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << file;
}

TEST(maneuvermap_sweep, help_and_list_show_the_sweeps) {
  const result help = run("--help", "help");
  EXPECT_TRUE(contains(help.out, "sweep")) << help.out;
  EXPECT_TRUE(contains(help.out, "plot")) << help.out;
  EXPECT_TRUE(contains(run("sweep --help", "sweep_help").out, "--jobs"));
  EXPECT_TRUE(contains(run("run --help", "run_help").out, "--plots"));
  const result list = run("list", "list");
  EXPECT_EQ(list.code, 0);
  EXPECT_TRUE(contains(list.out, "built-in sweeps")) << list.out;
  EXPECT_TRUE(contains(list.out, "  table1 ")) << list.out;
  EXPECT_TRUE(contains(list.out, "  roundabout ")) << list.out;
}

TEST(maneuvermap_sweep, a_good_sweep_exits_0_and_prints_its_table) {
  const temp_dir dir("sweep_ok");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [30, 40]\n"));
  const result ok = run("sweep " + (dir / "s.yaml").string() + " --jobs 2 --out " + (dir / "out").string(), "ok2");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(contains(ok.out, "| a_kmh | duration_s | policy |")) << ok.out;
  EXPECT_TRUE(contains(ok.out, "4 runs, 0 failed")) << ok.out;
  EXPECT_EQ(ok.err, "");  // no progress bar when standard error is not a terminal
  EXPECT_TRUE(std::filesystem::exists(dir / "out/runs.csv"));
}

TEST(maneuvermap_sweep, a_failed_run_exits_1_with_its_rerun_command) {
  const temp_dir dir("sweep_fail");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [-5, 30]\n"));
  const result r = run("sweep " + (dir / "s.yaml").string() + " --out " + (dir / "out").string(), "fail");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "run 0 failed")) << r.err;
  EXPECT_TRUE(contains(r.err, "maneuvermap run " + scenario + " --set a_kmh=-5 --set duration_s=1.5 --policy adj --seed 7"))
      << r.err;
  EXPECT_TRUE(contains(r.out, "4 runs, 2 failed")) << r.out;
}

TEST(maneuvermap_sweep, on_roads_runs_every_run_on_the_scenario_s_roads_and_says_so) {
  const temp_dir dir("sweep_on_roads");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [-5, 30]\n"));
  const result r = run("sweep " + (dir / "s.yaml").string() + " --on-roads --out " + (dir / "out").string(), "on_roads");
  EXPECT_EQ(r.code, 1) << r.err;  // the runs with a_kmh = -5 fail, as without --on-roads
  EXPECT_TRUE(contains(r.err, "--set a_kmh=-5 --set duration_s=1.5 --policy adj --seed 7 --on-roads")) << r.err;
  EXPECT_TRUE(contains(read_file(dir / "out/sweep.json"), "\"on_roads\": true")) << read_file(dir / "out/sweep.json");
  // A scenario with nothing to drive on is refused before any run.
  write_file(dir / "bare.yaml", R"(format: maneuvermap-scenario/1
name: bare
parameters: {a_kmh: 30}
agents:
  - {name: A, kind: planning_vehicle, desired_speed_kmh: $a_kmh,
     path: {start: {position_m: [0, 0], heading_deg: 0}, segments: [{straight_m: 50}]}}
)");
  write_file(dir / "bare-sweep.yaml", "format: maneuvermap-sweep/1\nname: bare\nscenario: " + (dir / "bare.yaml").string() +
                                           "\nparameters:\n  a_kmh: [30]\n");
  const result bare = run("sweep " + (dir / "bare-sweep.yaml").string() + " --on-roads --out " + (dir / "bare").string(),
                          "on_roads_bare");
  EXPECT_EQ(bare.code, 2) << bare.err;
  EXPECT_TRUE(contains(bare.err, "--on-roads: the scenario has no roads: and no roundabout:")) << bare.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bare/runs.csv"));
}

TEST(maneuvermap_sweep, a_bad_sweep_file_or_option_exits_2) {
  const temp_dir dir("sweep_bad");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [30, 40]\n", "jobs: 3\n"));
  const result r = run("sweep " + (dir / "s.yaml").string(), "bad_key");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "s.yaml:9:1: jobs: unknown key")) << r.err;
  EXPECT_EQ(run("sweep no-such-sweep", "bad_name").code, 2);
  const result zero_jobs = run("sweep table1 --jobs 0", "bad_jobs");
  EXPECT_EQ(zero_jobs.code, 2);
  EXPECT_TRUE(contains(zero_jobs.err, "--jobs: expected an integer from 1 to 256, got 0")) << zero_jobs.err;
  EXPECT_EQ(run("sweep table1 --repetitions 0", "bad_repetitions").code, 2);
  // 50 cells × 1000000 repetitions would be 5·10⁷ runs: refused before any run.
  const result too_many = run("sweep table1 --repetitions 1000000", "too_many_repetitions");
  EXPECT_EQ(too_many.code, 2);
  EXPECT_TRUE(contains(too_many.err, "--repetitions = 1000000: expected from 1 to 20000 (50 cells; at most 1000000 runs in all)"))
      << too_many.err;
}

TEST(maneuvermap_plot, missing_target_python_or_script_exit_2) {
  const temp_dir dir("plot_missing");
  EXPECT_EQ(run("plot " + (dir / "nothing").string(), "no_target").code, 2);
  const result python = run("plot " + dir.path().string(), "no_python", "MM_PYTHON=/nonexistent/python3");
  EXPECT_EQ(python.code, 2);
  EXPECT_TRUE(contains(python.err, "/nonexistent/python3")) << python.err;
  const result script = run("plot " + dir.path().string(), "no_script", "MM_PLOT_SCRIPT=/nonexistent/plot.py");
  EXPECT_EQ(script.code, 2);
  EXPECT_TRUE(contains(script.err, "MM_PLOT_SCRIPT")) << script.err;
}

TEST(maneuvermap_plot, a_python_without_matplotlib_exits_2_with_a_clear_message) {
  // A Python that cannot import matplotlib, whatever is installed: an empty module path.
  const temp_dir dir("plot_no_matplotlib");
  write_file(dir / "python", "#!/bin/sh\nexec /usr/bin/python3 -S -I \"$@\"\n");
  std::filesystem::permissions(dir / "python", std::filesystem::perms::owner_all);
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const result r = run("plot " + dir.path().string(), "no_matplotlib", "MM_PYTHON=" + (dir / "python").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "matplotlib")) << r.err;
}

TEST(maneuvermap_plot, a_directory_that_is_neither_a_run_nor_a_sweep_exits_2) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_empty");
  const result r = run("plot " + dir.path().string(), "empty");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "neither a run directory")) << r.err;
}

TEST(maneuvermap_plot, a_run_file_that_is_not_what_maneuvermap_writes_exits_2_naming_the_line_and_field) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_corrupt");
  const result r = run("run " + scenario + " --set duration_s=0.5 --out " + (dir / "run").string(), "run");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::filesystem::path trajectories = dir / "run" / "trajectories.csv";
  const std::string good = read_file(trajectories);
  // The header, the first row (t, agent, x, ..., with its newline) and the rest; x replaced in the first row.
  const std::size_t row_start = good.find('\n') + 1;
  const std::size_t row_end = good.find('\n', row_start) + 1;
  const std::string header = good.substr(0, row_start);
  const std::string first_row = good.substr(row_start, row_end - row_start);
  const std::string rest = good.substr(row_end);
  const std::size_t x_at = first_row.find(',', first_row.find(',') + 1) + 1;
  const std::size_t x_end = first_row.find(',', x_at);
  ASSERT_LT(x_at, x_end);
  const auto with_x = [&](const std::string& x) {
    return header + first_row.substr(0, x_at) + x + first_row.substr(x_end) + rest;
  };
  // A value that is not a number, one that is not finite, a column renamed, a row too long, no header.
  const struct {
    std::string text;
    std::string message;
  } cases[] = {
      {with_x("garbage"), "trajectories.csv:2: x = 'garbage': expected a number"},
      {with_x("nan"), "trajectories.csv:2: x = 'nan': expected a finite number"},
      {"t,agent,xx" + good.substr(good.find(",y,")), "trajectories.csv:2: no column 'x'"},
      {header + first_row.substr(0, first_row.size() - 1) + ",9\n" + rest, "trajectories.csv:2: more fields than the header's 8"},
      {"", "trajectories.csv: empty: expected a header line"},
  };
  for (const auto& c : cases) {
    write_file(trajectories, c.text);
    const result plotted = run("plot " + (dir / "run").string(), "corrupt");
    EXPECT_EQ(plotted.code, 2) << c.message << "\n" << plotted.err;
    EXPECT_TRUE(contains(plotted.err, c.message)) << plotted.err;
    EXPECT_FALSE(contains(plotted.err, "Traceback")) << plotted.err;
  }
}

TEST(maneuvermap_plot, run_with_plots_draws_the_map_speed_and_top_down_view) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_run");
  const result r = run("run " + scenario + " --set duration_s=1.5 --plots --out " + (dir / "run").string(), "run");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* name : {"map", "speed", "topdown"}) {
    expect_png(dir / "run" / (std::string(name) + ".png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "run" / (std::string(name) + ".svg"))) << name;
  }
  // Into another directory.
  const result again = run("plot " + (dir / "run").string() + " --out " + (dir / "figures").string(), "run_out");
  ASSERT_EQ(again.code, 0) << again.err;
  expect_png(dir / "figures/map.png");
}

TEST(maneuvermap_plot, measure_with_plots_draws_the_map_of_each_measured_road_user_and_the_scene_with_its_lanes) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_measure");
  const std::string recording = std::string(MM_TESTS_CLI_DIR) + "/../../data/commonroad/ZAM_Tutorial-1_2_T-1.xml";
  const result r = run("measure " + recording + " --agent all --plots --out " + (dir / "measured").string(), "measure");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* name : {"map-42", "map-44", "speed", "topdown", "rooms"}) expect_png(dir / "measured" / (std::string(name) + ".png"));
}

TEST(maneuvermap_plot, sweep_with_plots_draws_the_sweep_and_its_kept_runs) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_sweep");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [30, 40]\n", "keep_runs: true\n"));
  const result r =
      run("sweep " + (dir / "s.yaml").string() + " --repetitions 1 --plots --out " + (dir / "out").string(), "sweep");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_png(dir / "out/min-dist.png");
  expect_png(dir / "out/speed-profiles.png");
  expect_png(dir / "out/runs/a_kmh=30_duration_s=1.5_adj_rep0/map.png");
  expect_png(dir / "out/runs/a_kmh=40_duration_s=1.5_adj_rep0/topdown.png");
}

TEST(maneuvermap_plot, a_table1_shaped_sweep_is_drawn_beside_the_paper) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_table1");
  write_file(dir / "s.yaml", small_sweep("  a_kmh: [30]\n  b_kmh: [30, 35]\n"));
  const result r = run("sweep " + (dir / "s.yaml").string() + " --plots --out " + (dir / "out").string(), "table1");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_png(dir / "out/table1-comparison.png");
}

TEST(maneuvermap_plot, a_snapshot_is_drawn_as_displacement_sets) {
  REQUIRE_MATPLOTLIB();
  const temp_dir dir("plot_snapshot");
  const result shot =
      run("snapshot " + scenario + " --time 1.0 --agent A --out " + (dir / "shot.csv").string(), "snapshot");
  ASSERT_EQ(shot.code, 0) << shot.err;
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.json"));
  const result r = run("plot " + (dir / "shot.csv").string(), "snapshot_plot");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_png(dir / "shot-sets.png");
}

}  // namespace
