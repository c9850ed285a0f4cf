// `maneuvermap replay` as a user runs it on CommonRoad files: a run's files, byte-identical on a
// second run, the baseline without avoidance, and the exit code and message of each kind of bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli/support.hpp"

namespace {

using mm::cli::testing::contains;
using mm::cli::testing::csv_rows;
using mm::cli::testing::read_file;
using mm::cli::testing::temp_dir;
using result = mm::cli::testing::command_result;

std::string recording(const std::string& name) {
  return (std::filesystem::path(MM_SOURCE_DIR) / "data/commonroad" / (name + ".xml")).string();
}

result replay(const std::string& args, const temp_dir& dir) {
  return mm::cli::testing::run_command(MANEUVERMAP_EXE, "replay " + args, dir);
}

TEST(maneuvermap_replay, drives_the_recorded_ego_with_the_planner_and_writes_the_files_of_a_run_twice_alike) {
  const temp_dir dir("replay_ego");
  const std::string file = recording("OSC_PedestrianCollision-1_1_T-1");
  const result r = replay(file + " --out " + (dir / "run").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "road user 34 driven by the planner (avoiding), desired speed its recorded speeds")) << r.out;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "run" / name)) << name;
  }
  // The car and the pedestrian, every 10 ms while present; the car plans at every step but the last
  // (the crash ends the run, and nothing is planned at the instant a run ends).
  std::size_t car = 0;
  std::size_t pedestrian = 0;
  for (const auto& row : csv_rows(dir / "run/trajectories.csv")) {
    car += row[1] == "car-34";
    pedestrian += row[1] == "pedestrian-35";
  }
  EXPECT_GT(car, 500U);
  EXPECT_EQ(pedestrian, car);
  EXPECT_EQ(csv_rows(dir / "run/decisions.csv").size() + 1, car);
  EXPECT_TRUE(contains(read_file(dir / "run/scene.json"), "\"name\":\"lanelet ")) << "the lanes, drawn as roads";

  const result again = replay(file + " --out " + (dir / "again").string(), dir);
  ASSERT_EQ(again.code, 0) << again.err;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
    EXPECT_EQ(read_file(dir / "run" / name), read_file(dir / "again" / name)) << name;
  }
}

TEST(maneuvermap_replay, writes_the_replay_as_a_scenario_file_that_runs_as_the_replay_does) {
  const temp_dir dir("replay_scenario");
  const std::string file = recording("OSC_PedestrianCollision-1_1_T-1");
  const std::string scenario = (dir / "replay.yaml").string();
  const result r = replay(file + " --reactive --on-lanelets --out " + (dir / "replay").string() + " --write-scenario " + scenario, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(read_file(scenario), "desired_speed_profile:")) << "its recorded speeds";
  EXPECT_TRUE(contains(read_file(scenario), "open_edges:")) << "the lanelets' open ends";
  const result run = mm::cli::testing::run_command(MANEUVERMAP_EXE, "run " + scenario + " --out " + (dir / "run").string(), dir);
  ASSERT_EQ(run.code, 0) << run.err;
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "scene.json"}) {
    const std::string a = read_file(dir / "replay" / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, read_file(dir / "run" / name)) << name;
  }
}

TEST(maneuvermap_replay, without_avoidance_the_car_keeps_its_speed_and_path_and_no_map_is_computed) {
  const temp_dir dir("replay_baseline");
  const result r = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " --no-avoidance --desired-speed 30 --out " +
                              (dir / "run").string(),
                          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "(without avoidance), desired speed 30.0 km/h")) << r.out;
  EXPECT_TRUE(csv_rows(dir / "run/map.csv").empty());
}

TEST(maneuvermap_replay, with_reactive_traffic_the_car_behind_the_driven_one_keeps_its_distance_and_no_other_changes) {
  // USA_Lanker-1_1: car 1216 drives 14 m behind car 1214, closer than car following's desired gap.
  // Replayed as recorded, every other road user is where it was recorded; reacting, car 1216 falls
  // behind its recording, and the road users that follow none that deviates keep to theirs.
  const temp_dir dir("replay_reactive");
  const std::string file = recording("USA_Lanker-1_1_T-1") + " --agent 1214 --out ";
  const result plain = replay(file + (dir / "plain").string(), dir);
  ASSERT_EQ(plain.code, 0) << plain.err;
  const result reactive = replay(file + (dir / "reactive").string() + " --reactive", dir);
  ASSERT_EQ(reactive.code, 0) << reactive.err;
  EXPECT_TRUE(contains(reactive.out, "the others replayed, reacting (car following)")) << reactive.out;
  EXPECT_FALSE(contains(plain.out, "reacting")) << plain.out;
  const auto rows_of = [&](const char* run) {
    std::map<std::string, std::vector<std::vector<std::string>>> rows;
    for (const auto& row : csv_rows(dir / run / "trajectories.csv")) rows[row[1]].push_back(row);
    return rows;
  };
  const auto as_recorded = rows_of("plain");
  const auto reacting = rows_of("reactive");
  ASSERT_EQ(as_recorded.size(), reacting.size());
  std::vector<std::string> changed;
  for (const auto& [name, rows] : as_recorded) {
    if (name != "car-1214" && reacting.at(name) != rows) changed.push_back(name);
  }
  EXPECT_EQ(changed, std::vector<std::string>{"car-1216"});
}

TEST(maneuvermap_replay, bad_input_exits_2_with_a_message_that_says_what_was_wrong) {
  const temp_dir dir("replay_bad");
  const std::string out = " --out " + (dir / "run").string();
  const result no_ego = replay(recording("ZAM_Tutorial-1_2_T-1") + out, dir);
  EXPECT_EQ(no_ego.code, 2);
  EXPECT_TRUE(contains(no_ego.err, "give --agent ID, one of: 42, 44")) << no_ego.err;
  const result unknown = replay(recording("ZAM_Tutorial-1_2_T-1") + " --agent 999" + out, dir);
  EXPECT_EQ(unknown.code, 2);
  EXPECT_TRUE(contains(unknown.err, "ZAM_Tutorial-1_2_T-1.xml: road user 999: no obstacle has this id")) << unknown.err;
  const result pedestrian = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " --agent 35" + out, dir);
  EXPECT_EQ(pedestrian.code, 2);
  EXPECT_TRUE(contains(pedestrian.err, "a pedestrian")) << pedestrian.err;
  const result missing = replay((dir / "no-such-file.xml").string() + out, dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_TRUE(contains(missing.err, "no-such-file.xml")) << missing.err;
  for (const char* option : {"--agent 0", "--agent abc", "--policy sometimes", "--policy const:0.3", "--desired-speed -5"}) {
    const result bad = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " " + option + out, dir);
    EXPECT_EQ(bad.code, 2) << option << ": " << bad.err;
    EXPECT_TRUE(contains(bad.err, "maneuvermap: ")) << option << ": " << bad.err;
  }
  const result zero = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " --agent 0" + out, dir);
  EXPECT_TRUE(contains(zero.err, "--agent: expected the id of the one road user to drive (replay drives one; measure takes "
                                 "all), an integer from 1 to 4294967295, got 0"))
      << zero.err;
  const result all = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " --agent all" + out, dir);
  EXPECT_TRUE(contains(all.err, "replay drives one; measure takes all")) << all.err;
  const result off_grid = replay(recording("OSC_PedestrianCollision-1_1_T-1") + " --policy const:9" + out, dir);
  EXPECT_TRUE(contains(off_grid.err, "--policy const:9: config.policy.constant_forecast_time = 9: expected a forecast time "
                                     "on the grid"))
      << off_grid.err;
}

}  // namespace
