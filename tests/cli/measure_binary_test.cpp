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

TEST(maneuvermap_measure, on_lanelets_counts_only_the_room_on_the_road_and_says_so) {
  // USA_Lanker-1_1: a signalised intersection of recorded traffic; its lanelets are the road.
  const temp_dir dir("measure_on_lanelets");
  const std::string file = recording("USA_Lanker-1_1_T-1") + " --agent 1213 --agent 1214";
  ASSERT_EQ(measure(file + " --out " + (dir / "open").string(), dir).code, 0);
  const result r = measure(file + " --on-lanelets --out " + (dir / "road").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string summary = read_file(dir / "road/summary.json");
  EXPECT_TRUE(contains(summary, "\"drivable_area\": \"lanelets\"")) << summary;
  EXPECT_TRUE(contains(read_file(dir / "open/summary.json"), "\"drivable_area\": null"));
  EXPECT_TRUE(contains(summary, "\"steps_on_drivable_area\": ")) << summary;
  EXPECT_TRUE(contains(read_file(dir / "road/scene.json"), "\"drivable_area\":{\"boundary_m\":[[["));
  EXPECT_TRUE(contains(read_file(dir / "open/scene.json"), "\"drivable_area\":null"));
  // Step by step the road takes room, never gives it (up to the interpolation's rounding).
  const auto open = csv_rows(dir / "open/rooms.csv");
  const auto road = csv_rows(dir / "road/rooms.csv");
  ASSERT_EQ(open.size(), road.size());
  std::size_t less = 0;
  for (std::size_t k = 0; k < open.size(); ++k) {
    EXPECT_LE(std::stod(road[k][3]), std::stod(open[k][3]) + 1e-4) << road[k][0] << " " << road[k][1];
    less += std::stod(road[k][3]) < std::stod(open[k][3]) - 0.01 ? 1 : 0;
  }
  EXPECT_GT(less, 0U);
}

TEST(maneuvermap_measure, several_files_go_each_into_a_folder_of_its_name_and_into_one_table_of_every_road_user) {
  const temp_dir dir("measure_several");
  const std::string tutorial = recording("ZAM_Tutorial-1_2_T-1");
  const std::string pedestrian = recording("OSC_PedestrianCollision-1_1_T-1");
  const result r = measure(tutorial + " " + pedestrian + " --agent all --out " + (dir / "all").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "2 files, 3 road users")) << r.out;
  // Each file's own outputs, the same bytes as when it is measured alone.
  ASSERT_EQ(measure(pedestrian + " --agent all --out " + (dir / "alone").string(), dir).code, 0);
  for (const char* file : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json", "rooms.csv"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "all/ZAM_Tutorial-1_2_T-1" / file)) << file;
    EXPECT_EQ(read_file(dir / "all/OSC_PedestrianCollision-1_1_T-1" / file), read_file(dir / "alone" / file)) << file;
  }
  // One row per road user, in the files' order, with its summary's values.
  std::string header;
  const auto rows = csv_rows(dir / "all/measurements.csv", &header);
  EXPECT_EQ(header, "file,agent,steps,least_room,least_room_time_s,unsafe_steps,earliest_ttc_s,earliest_ttc_time_s");
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rows[0][0], "ZAM_Tutorial-1_2_T-1");
  EXPECT_EQ(rows[0][1], "42");
  EXPECT_EQ(rows[1][1], "44");
  EXPECT_EQ(rows[1][6], "") << "44 is never on a collision course";
  EXPECT_EQ(rows[2][0], "OSC_PedestrianCollision-1_1_T-1");
  EXPECT_EQ(rows[2][1], "34");
  EXPECT_EQ(rows[2][2], "93");
  EXPECT_EQ(rows[2][3], "0.000000") << "it drives into the pedestrian";
  const std::string summary = read_file(dir / "alone/summary.json");
  EXPECT_TRUE(contains(summary, "\"unsafe_steps\": " + rows[2][5])) << summary;

  // Without --agent each file's recorded ego. Every file is checked before anything is measured:
  // each one that cannot be is named, and nothing is written.
  const std::string tjunction = recording("ZAM_Intersection-1_1_T-1");
  const result no_ego =
      measure(pedestrian + " " + tutorial + " " + tjunction + " " + (dir / "no-such-file.xml").string() + " --out " +
                  (dir / "egos").string(),
              dir);
  EXPECT_EQ(no_ego.code, 2);
  EXPECT_TRUE(contains(no_ego.err, "3 of the 4 files cannot be measured; nothing was measured:\n")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "ZAM_Tutorial-1_2_T-1.xml: no obstacle of the file replays the ego")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "ZAM_Intersection-1_1_T-1.xml: no obstacle of the file replays the ego")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "no-such-file.xml: cannot open the file")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "with several files, --agent all measures every road user of each")) << no_ego.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "egos")) << "nothing is measured when a file cannot be";

  const result twice = measure(tutorial + " " + tutorial + " --agent all --out " + (dir / "twice").string(), dir);
  EXPECT_EQ(twice.code, 2);
  EXPECT_TRUE(contains(twice.err, "two files named ZAM_Tutorial-1_2_T-1")) << twice.err;
  const result ids = measure(tutorial + " " + pedestrian + " --agent 42 --out " + (dir / "ids").string(), dir);
  EXPECT_EQ(ids.code, 2);
  EXPECT_TRUE(contains(ids.err, "with several files give --agent all")) << ids.err;
  const result broken = measure(tutorial + " " + (dir / "no-such-file.xml").string() + " --agent all --out " +
                                    (dir / "broken").string(),
                                dir);
  EXPECT_EQ(broken.code, 2);
  EXPECT_TRUE(contains(broken.err, "no-such-file.xml")) << broken.err;
}

TEST(maneuvermap_measure, several_files_on_any_number_of_threads_give_the_same_bytes) {
  // The road users of all the files are measured by one pool of threads, file after file.
  const temp_dir dir("measure_several_jobs");
  const std::string files = recording("ZAM_Tutorial-1_2_T-1") + " " + recording("OSC_PedestrianCollision-1_1_T-1") +
                            " " + recording("ZAM_Intersection-1_1_T-1") + " --agent all";
  ASSERT_EQ(measure(files + " --jobs 1 --out " + (dir / "one").string(), dir).code, 0);
  const result three = measure(files + " --jobs 3 --out " + (dir / "three").string(), dir);
  ASSERT_EQ(three.code, 0) << three.err;
  EXPECT_TRUE(contains(three.out, "3 files, 5 road users")) << three.out;
  std::size_t compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir / "one")) {
    if (!entry.is_regular_file()) continue;
    const std::filesystem::path relative = std::filesystem::relative(entry.path(), dir / "one");
    EXPECT_EQ(read_file(entry.path()), read_file(dir / "three" / relative)) << relative;
    ++compared;
  }
  EXPECT_EQ(compared, 3U * 6U + 1U) << "six files per recording and measurements.csv";
}

TEST(maneuvermap_measure, bad_input_exits_2_with_a_message_that_says_what_was_wrong) {
  const temp_dir dir("measure_bad");
  write_file(dir / "broken.xml", "<commonRoad timeStepSize=\"0.1\" commonRoadVersion=\"2020a\">\n<lanelet id=\"1\">\n");
  const result broken = measure((dir / "broken.xml").string(), dir);
  EXPECT_EQ(broken.code, 2);
  EXPECT_TRUE(contains(broken.err, "broken.xml")) << broken.err;

  const result missing = measure((dir / "no-such-file.xml").string(), dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_TRUE(contains(missing.err, "no-such-file.xml: cannot open the file: No such file or directory")) << missing.err;

  const result no_ego = measure(recording("ZAM_Tutorial-1_2_T-1") + " --out " + (dir / "run").string(), dir);
  EXPECT_EQ(no_ego.code, 2);
  EXPECT_TRUE(contains(no_ego.err, "--agent ID")) << no_ego.err;
  EXPECT_TRUE(contains(no_ego.err, "42, 44")) << no_ego.err;

  const result unknown = measure(recording("ZAM_Tutorial-1_2_T-1") + " --agent 999 --out " + (dir / "run").string(), dir);
  EXPECT_EQ(unknown.code, 2);
  EXPECT_TRUE(contains(unknown.err, "ZAM_Tutorial-1_2_T-1.xml: road user 999: no obstacle has this id")) << unknown.err;

  const result pedestrian =
      measure(recording("OSC_PedestrianCollision-1_1_T-1") + " --agent 35 --out " + (dir / "run").string(), dir);
  EXPECT_EQ(pedestrian.code, 2);
  EXPECT_TRUE(contains(pedestrian.err, "a pedestrian")) << pedestrian.err;

  for (const char* option : {"--agent abc", "--agent 0", "--agent all --agent 42", "--agent 42 --agent 42", "--policy const:0.3", "--jobs 0"}) {
    const result r = measure(recording("ZAM_Tutorial-1_2_T-1") + " " + option + " --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.code, 2) << option << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "maneuvermap: ")) << option << ": " << r.err;
  }
  // Option values are named with what was expected, before any file is read.
  const std::vector<std::pair<std::string, std::string>> messages = {
      {"--policy const:0.3", "--policy const:0.3: config.policy.constant_forecast_time = 0.3: expected a forecast time on the grid"},
      {"--jobs abc", "--jobs: expected an integer from 1 to 256, got abc"},
      {recording("USA_Lanker-1_1_T-1") + " --agent 42", "--agent 42: an id names a road user of one file"}};
  for (const auto& [option, message] : messages) {
    const result r = measure(recording("ZAM_Tutorial-1_2_T-1") + " " + option + " --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.code, 2) << option << ": " << r.err;
    EXPECT_TRUE(contains(r.err, message)) << option << ": " << r.err;
  }
}

}  // namespace
