// The built `maneuvermap` executable: help, exit codes and messages.
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

/// Runs `maneuvermap ARGS` (ARGS is shell text) with its output captured.
result run(const std::string& args, const std::string& tag) {
  const temp_dir dir("binary_" + tag);
  return mm::cli::testing::run_command(MANEUVERMAP_EXE, args, dir);
}

TEST(maneuvermap, help_lists_the_commands_and_exits_0) {
  const result r = run("--help", "help");
  EXPECT_EQ(r.code, 0);
  for (const char* command : {"list", "validate", "resolve", "run", "snapshot", "measure"}) EXPECT_TRUE(contains(r.out, command)) << r.out;
}

TEST(maneuvermap, every_command_has_help) {
  for (const char* command : {"list", "validate", "resolve", "run", "snapshot", "measure"}) {
    const result r = run(std::string(command) + " --help", std::string("help_") + command);
    EXPECT_EQ(r.code, 0) << command;
    EXPECT_TRUE(contains(r.out, command)) << r.out;
  }
  EXPECT_TRUE(contains(run("run --help", "help_run_options").out, "--policy"));
  EXPECT_TRUE(contains(run("snapshot --help", "help_snapshot_options").out, "--tau"));
}

TEST(maneuvermap, no_command_an_unknown_command_and_an_unknown_option_exit_2) {
  EXPECT_EQ(run("", "none").code, 2);
  const result unknown = run("fly", "unknown");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_TRUE(contains(unknown.err, "maneuvermap:")) << unknown.err;
  EXPECT_EQ(run("run s1-crossing --fast", "unknown_option").code, 2);
  EXPECT_EQ(run("run", "missing_file").code, 2);
}

TEST(maneuvermap, list_names_every_built_in_scenario) {
  const result r = run("list", "list");
  EXPECT_EQ(r.code, 0);
  for (const char* name : {"s1-crossing", "s1-crossing-no-steering", "s2-roundabout", "s3-left-turn", "s4-pedestrian",
                           "s4-pedestrian-kerb", "s5-several-obstacles"}) {
    EXPECT_TRUE(contains(r.out, std::string(name) + " ")) << name;
  }
}

TEST(maneuvermap, validate_accepts_a_built_in_and_prints_its_timing) {
  const result r = run("validate s3-left-turn", "validate_ok");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "meet A and B: 47.000 m")) << r.out;
}

TEST(maneuvermap, validate_reports_a_bad_file_with_its_line_and_exits_2) {
  const temp_dir dir("validate_bad");
  write_file(dir / "bad.yaml", "format: maneuvermap-scenario/1\nname: bad\nduration_s: -3\nagents: []\n");
  const result r = run("validate " + (dir / "bad.yaml").string(), "validate_bad");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "bad.yaml:3:13: duration_s = -3: expected a positive number [s]")) << r.err;
}

TEST(maneuvermap, an_unknown_scenario_exits_2_and_suggests_a_built_in) {
  const result r = run("run s4-pedestrain", "unknown_scenario");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "did you mean s4-pedestrian?")) << r.err;
  EXPECT_EQ(run("validate /no/such/file.yaml", "missing").code, 2);
}

TEST(maneuvermap, bad_option_values_exit_2) {
  struct bad_option {
    const char* args;
    const char* label;
    const char* message;  ///< what the error must say; empty: only the exit code is checked
  };
  const bad_option cases[] = {
      {"run s1-crossing --policy sideways", "bad_policy", "--policy sideways: expected adj, const:SECONDS or robust"},
      {"run s1-crossing --policy const:0.3", "off_grid_policy",
       "builtin:s1-crossing: --policy const:0.3: planner.policy.constant_forecast_time = 0.3: expected a forecast time on "
       "the grid"},
      {"run s1-crossing --jobs many", "bad_jobs", "--jobs: expected an integer from 1 to 256, got many"},
      {"snapshot s1-crossing --time soon --agent A", "word_time", "--time: expected a number of seconds, got soon"},
      {"run s1-crossing --seed minus", "bad_seed", ""},
      // A negative seed is refused, not wrapped around to 2^64 − 5.
      {"run s1-crossing --seed -5", "negative_seed", "expected an integer from 0 to 18446744073709551615, got -5"},
      {"run s1-crossing --set a_kmh", "bad_set", ""},
      {"run s1-crossing --set speed_kmh=3", "unknown_parameter", "--set speed_kmh: unknown parameter"},
      {"snapshot s1-crossing --time 9 --agent A", "late_snapshot", ""},
      {"snapshot s1-crossing --time nan --agent A", "nan_snapshot", "--time nan: expected a time from 0 to the duration 8.000 s"},
      {"snapshot s1-crossing --time 1 --agent A --tau 1e300", "huge_tau", "--tau 1e+300: not on the forecast grid"},
      {"snapshot s1-crossing --time 1 --agent C", "unknown_agent", ""},
      {"snapshot s1-crossing --time 1", "missing_agent", ""},
  };
  for (const bad_option& c : cases) {
    const result r = run(c.args, c.label);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << c.args << ": " << r.err;
  }
}

TEST(maneuvermap, run_writes_the_five_files_and_prints_the_metrics) {
  const temp_dir dir("run_ok");
  write_file(dir / "short.yaml", R"(format: maneuvermap-scenario/1
name: short
duration_s: 0.3
parameters: {v_mps: 10}
agents:
  - {name: A, kind: planning_vehicle, desired_speed_mps: $v_mps,
     path: {start: {position_m: [0, 0], heading_deg: 0}, segments: [{straight_m: 100}]}}
)");
  const result r = run("run " + (dir / "short.yaml").string() + " --set v_mps=12 --policy const:0.5 --seed 3 --out " +
                           (dir / "out").string(),
                       "run_ok");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "short: policy const:0.5, seed 3")) << r.out;
  EXPECT_TRUE(contains(r.out, "min_dist_m")) << r.out;
  EXPECT_TRUE(r.err.empty()) << "no progress when stderr is not a terminal: " << r.err;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
    EXPECT_FALSE(read_file(dir / "out" / name).empty()) << name;
  }
  EXPECT_TRUE(contains(read_file(dir / "out" / "summary.json"), "\"v_mps\": 12.0")) << read_file(dir / "out" / "summary.json");
}

TEST(maneuvermap, run_with_two_planning_threads_writes_the_same_bytes_as_with_one) {
  const temp_dir dir("run_jobs");
  // Three planning vehicles that meet at a crossing: each one avoids the other two.
  write_file(dir / "three.yaml", R"(format: maneuvermap-scenario/1
name: three
duration_s: 0.3
agents:
  - {name: A, kind: planning_vehicle, desired_speed_mps: 10,
     path: {start: {position_m: [-25, 0], heading_deg: 0}, segments: [{straight_m: 100}]}}
  - {name: B, kind: planning_vehicle, desired_speed_mps: 10,
     path: {start: {position_m: [0, 25], heading_deg: -90}, segments: [{straight_m: 100}]}}
  - {name: C, kind: planning_vehicle, desired_speed_mps: 10,
     path: {start: {position_m: [25, 1.5], heading_deg: 180}, segments: [{straight_m: 100}]}}
)");
  const std::string scenario = (dir / "three.yaml").string();
  const result one = run("run " + scenario + " --jobs 1 --out " + (dir / "one").string(), "run_jobs_1");
  const result two = run("run " + scenario + " --jobs 2 --out " + (dir / "two").string(), "run_jobs_2");
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_EQ(one.out.substr(0, one.out.find("written to")), two.out.substr(0, two.out.find("written to")));
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
    const std::string a = read_file(dir / "one" / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, read_file(dir / "two" / name)) << name;
  }
  EXPECT_EQ(run("run " + scenario + " --jobs 0", "run_jobs_0").code, 2);
}

TEST(maneuvermap, snapshot_writes_csv_to_standard_output) {
  const result r = run("snapshot s1-crossing-no-steering --time 0.2 --agent A --tau 0", "snapshot_ok");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("tau,family,accel,curvature,end_x,end_y,area_weight,safe,selected\n0.000000,brake,", 0), 0U) << r.out;
}

TEST(maneuvermap, an_output_directory_that_cannot_be_created_is_an_error_with_exit_1) {
  const result r = run("run s4-pedestrian-kerb --out /dev/null/out", "unwritable");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "maneuvermap: error:")) << r.err;
}

TEST(maneuvermap, on_roads_plans_s2_on_its_lanes_as_the_example_file_does_and_refuses_a_second_drivable_area) {
  const temp_dir dir("on_roads");
  const std::string example = std::string(MM_SOURCE_DIR) + "/examples/scenarios/s2-roundabout-road.yaml";
  const result flag = run("run s2-roundabout --on-roads --out " + (dir / "flag").string(), "on_roads_flag");
  const result file = run("run " + example + " --out " + (dir / "file").string(), "on_roads_file");
  ASSERT_EQ(flag.code, 0) << flag.err;
  ASSERT_EQ(file.code, 0) << file.err;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv"}) {
    const std::string a = read_file(dir / "flag" / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, read_file(dir / "file" / name)) << name << ": --on-roads and drivable_area: {roundabout: true} differ";
  }
  ASSERT_EQ(run("run s2-roundabout --out " + (dir / "open").string(), "on_roads_open").code, 0);
  EXPECT_NE(read_file(dir / "flag/trajectories.csv"), read_file(dir / "open/trajectories.csv")) << "the lanes change A's run";
  const result twice = run("validate " + example + " --on-roads", "on_roads_twice");
  EXPECT_EQ(twice.code, 2);
  EXPECT_TRUE(contains(twice.err, "--on-roads: the scenario gives its own drivable_area: (line 36)")) << twice.err;
}

TEST(maneuvermap, resolve_writes_a_file_that_runs_as_the_scenario_does) {
  const temp_dir dir("resolve");
  const std::string options = " --on-roads --set b_kmh=38 --policy robust --seed 4";
  const result written = run("resolve s2-roundabout" + options + " --out " + (dir / "s2.yaml").string(), "resolve_file");
  ASSERT_EQ(written.code, 0) << written.err;
  const std::string text = read_file(dir / "s2.yaml");
  EXPECT_TRUE(contains(text, "policy: robust")) << text;
  EXPECT_TRUE(contains(text, "seed: 4")) << text;
  EXPECT_FALSE(contains(text, "meet:")) << text;
  const result printed = run("resolve s2-roundabout" + options, "resolve_print");
  ASSERT_EQ(printed.code, 0) << printed.err;
  EXPECT_EQ(printed.out, text);

  ASSERT_EQ(run("run s2-roundabout" + options + " --out " + (dir / "original").string(), "resolve_original").code, 0);
  const result again = run("run " + (dir / "s2.yaml").string() + " --out " + (dir / "resolved").string(), "resolve_run");
  ASSERT_EQ(again.code, 0) << again.err;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "scene.json"}) {
    const std::string a = read_file(dir / "original" / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, read_file(dir / "resolved" / name)) << name;
  }
  // The file resolves to itself.
  const result twice = run("resolve " + (dir / "s2.yaml").string(), "resolve_twice");
  ASSERT_EQ(twice.code, 0) << twice.err;
  EXPECT_EQ(twice.out, text);

  const result unwritable = run("resolve s1-crossing --out /dev/null/s1.yaml", "resolve_unwritable");
  EXPECT_EQ(unwritable.code, 1);
  EXPECT_TRUE(contains(unwritable.err, "maneuvermap: error: /dev/null/s1.yaml: cannot write the file")) << unwritable.err;
  const result bad = run("resolve s1-crossing --set b_kmh=-5", "resolve_bad");
  EXPECT_EQ(bad.code, 2);
  EXPECT_TRUE(bad.out.empty()) << bad.out;
}

TEST(maneuvermap, a_run_written_as_a_commonroad_recording_is_measured_as_a_recording) {
  const temp_dir dir("run_commonroad");
  const std::string xml = (dir / "s5.xml").string();
  const result r = run("run s5-several-obstacles --out " + (dir / "run").string() + " --commonroad " + xml, "run_commonroad");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(read_file(dir / "s5.xml"), "commonRoadVersion=\"2020a\"")) << read_file(dir / "s5.xml");
  const result measured = run("measure " + xml + " --agent all --out " + (dir / "measured").string(), "measure_commonroad");
  ASSERT_EQ(measured.code, 0) << measured.err;
  EXPECT_TRUE(contains(measured.out, "s5: CommonRoad 2020a, 4 road users and obstacles, time step 0.100 s")) << measured.out;
  const result off_grid = run("run s5-several-obstacles --out " + (dir / "never").string() + " --commonroad " + xml +
                                  " --commonroad-step 0.025",
                              "run_commonroad_off_grid");
  EXPECT_EQ(off_grid.code, 2);
  EXPECT_TRUE(contains(off_grid.err, "--commonroad-step 0.025000: expected a whole multiple of the run's time step")) << off_grid.err;
}

TEST(maneuvermap, a_roundabout_run_written_as_a_commonroad_recording_is_measured_on_its_lanes) {
  const temp_dir dir("run_commonroad_lanes");
  const std::string xml = (dir / "s2.xml").string();
  const result r = run("run s2-roundabout --out " + (dir / "run").string() + " --commonroad " + xml, "run_commonroad_s2");
  ASSERT_EQ(r.code, 0) << r.err;
  const result measured =
      run("measure " + xml + " --agent all --on-lanelets --out " + (dir / "measured").string(), "measure_commonroad_s2");
  ASSERT_EQ(measured.code, 0) << measured.err;
  // Both cars start every step on the recording's lanelets: on the ring's and the arms' lanes.
  const std::string summary = read_file(dir / "measured" / "summary.json");
  EXPECT_TRUE(contains(summary, "\"drivable_area\": \"lanelets\"")) << summary;
  EXPECT_TRUE(contains(summary, "\"steps\": 45,\n      \"steps_on_drivable_area\": 45")) << summary;
  EXPECT_TRUE(contains(summary, "\"steps\": 51,\n      \"steps_on_drivable_area\": 51")) << summary;
}

}  // namespace
