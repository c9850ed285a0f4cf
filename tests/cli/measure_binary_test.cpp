// `maneuvermap measure` as a user runs it on CommonRoad files: the files it writes, that they are
// reproducible, and the exit code and message of each kind of bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/support.hpp"

namespace {

using mm::cli::testing::contains;
using mm::cli::testing::csv_rows;
using mm::cli::testing::read_file;
using mm::cli::testing::temp_dir;
using mm::cli::testing::write_file;
using result = mm::cli::testing::command_result;

std::string recording(const std::string& name) {
  return (std::filesystem::path(MM_SOURCE_DIR) / "data/commonroad" / (name + ".xml")).string();
}

result measure(const std::string& args, const temp_dir& dir) {
  return mm::cli::testing::run_command(MANEUVERMAP_EXE, "measure " + args, dir);
}

TEST(maneuvermap_measure, measures_the_recorded_ego_of_the_planning_problem_at_every_recorded_step) {
  const temp_dir dir("measure_ego");
  const result r = measure(recording("OSC_PedestrianCollision-1_1_T-1") + " --out " + (dir / "run").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // Car 34 replays the planning problem's ego (the same id); it drives into the pedestrian.
  EXPECT_TRUE(contains(r.out, "        34     93")) << r.out;
  for (const char* file : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json", "rooms.csv"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "run" / file)) << file;
  }
  std::string header;
  const auto map = csv_rows(dir / "run/map.csv", &header);
  EXPECT_EQ(header, "t,agent,tau,mi_brake,mi_accel,excluded");
  EXPECT_EQ(map.size(), 93U * 17U);
  const auto decisions = csv_rows(dir / "run/decisions.csv");
  ASSERT_EQ(decisions.size(), 93U);
  bool near_crash = false;
  for (const auto& row : decisions) near_crash = near_crash || row[4] == "near_crash";
  EXPECT_TRUE(near_crash) << "the recording ends in a collision with the pedestrian";
  // rooms.csv: a row per step, the room 1 before the pedestrian comes near and 0 at the collision.
  const auto rooms = csv_rows(dir / "run/rooms.csv", &header);
  EXPECT_EQ(header, "t,agent,speed,room,mode,ttc");
  ASSERT_EQ(rooms.size(), 93U);
  EXPECT_EQ(rooms.front()[3], "1.000000");
  EXPECT_EQ(rooms[56][0], "5.600000");
  EXPECT_EQ(rooms[56][3], "0.000000");
  EXPECT_TRUE(contains(read_file(dir / "run/summary.json"), "\"format\": \"maneuvermap-measurement/1\""));
  const std::string scene = read_file(dir / "run/scene.json");
  EXPECT_TRUE(contains(scene, "\"lanelets\":[{")) << scene.substr(0, 200);
  EXPECT_TRUE(contains(scene, "\"kind\":\"planning_vehicle\",\"type\":\"car\"")) << scene.substr(0, 400);
}

TEST(maneuvermap_measure, gives_byte_identical_files_on_every_run_on_any_number_of_threads) {
  const temp_dir dir("measure_twice");
  // Once on one thread, once on two: the files do not depend on it.
  ASSERT_EQ(measure(recording("USA_Lanker-1_1_T-1") + " --agent 1213 --agent 1214 --jobs 1 --out " + (dir / "a").string(), dir).code, 0);
  ASSERT_EQ(measure(recording("USA_Lanker-1_1_T-1") + " --agent 1213 --agent 1214 --jobs 2 --out " + (dir / "b").string(), dir).code, 0);
  for (const char* file : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json", "rooms.csv"}) {
    EXPECT_EQ(read_file(dir / "a" / file), read_file(dir / "b" / file)) << file;
  }
  EXPECT_EQ(csv_rows(dir / "a/decisions.csv").size(), 2U * 41U);
}

TEST(maneuvermap_measure, agent_all_measures_every_vehicle_and_no_pedestrian_or_parked_car) {
  const temp_dir dir("measure_all");
  const result r = measure(recording("ZAM_Tutorial-1_2_T-1") + " --agent all --out " + (dir / "run").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "        42     41")) << r.out;
  EXPECT_TRUE(contains(r.out, "        44     41")) << r.out;
  EXPECT_FALSE(contains(r.out, "        43 ")) << r.out;  // the parked vehicle
}

TEST(maneuvermap_measure, bad_input_exits_2_with_a_message_that_says_what_was_wrong) {
  const temp_dir dir("measure_bad");
  write_file(dir / "broken.xml", "<commonRoad timeStepSize=\"0.1\" commonRoadVersion=\"2020a\">\n<lanelet id=\"1\">\n");
  const result broken = measure((dir / "broken.xml").string(), dir);
  EXPECT_EQ(broken.code, 2);
  EXPECT_TRUE(contains(broken.err, "broken.xml")) << broken.err;

  const result missing = measure((dir / "no-such-file.xml").string(), dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_TRUE(contains(missing.err, "no-such-file.xml")) << missing.err;

  const result no_ego = measure(recording("ZAM_Tutorial-1_2_T-1") + " --out " + (dir / "run").string(), dir);
  EXPECT_EQ(no_ego.code, 2);
  EXPECT_TRUE(contains(no_ego.err, "--agent ID")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "42, 44")) << no_ego.err;

  const result unknown = measure(recording("ZAM_Tutorial-1_2_T-1") + " --agent 999 --out " + (dir / "run").string(), dir);
  EXPECT_EQ(unknown.code, 2);
  EXPECT_TRUE(contains(unknown.err, "road user 999: no obstacle has this id")) << unknown.err;

  const result pedestrian =
      measure(recording("OSC_PedestrianCollision-1_1_T-1") + " --agent 35 --out " + (dir / "run").string(), dir);
  EXPECT_EQ(pedestrian.code, 2);
  EXPECT_TRUE(contains(pedestrian.err, "a pedestrian")) << pedestrian.err;

  for (const char* option : {"--agent abc", "--agent 0", "--agent all --agent 42", "--agent 42 --agent 42", "--policy const:0.3", "--jobs 0"}) {
    const result r = measure(recording("ZAM_Tutorial-1_2_T-1") + " " + option + " --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.code, 2) << option << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "maneuvermap: ")) << option << ": " << r.err;
  }
}

}  // namespace
