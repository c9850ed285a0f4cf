// Reading CommonRoad files: the real files of data/commonroad (and of the shared collection when
// it is there), the shapes and state layouts the format allows, and every error's message: the
// source, the line, the element path, the value found and what was expected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "mm/commonroad/reader.hpp"

namespace {

using namespace mm::commonroad;

std::filesystem::path source_dir() {
  const char* root = std::getenv("MM_SOURCE_DIR");
  return root ? std::filesystem::path(root) : std::filesystem::path(".");
}

std::filesystem::path data_file(const std::string& name) { return source_dir() / "data/commonroad" / name; }

std::vector<std::filesystem::path> xml_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".xml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const obstacle& find_obstacle(const scenario& s, std::uint32_t id) {
  for (const obstacle& o : s.obstacles) {
    if (o.id == id) return o;
  }
  throw std::runtime_error("no obstacle " + std::to_string(id));
}

/// What every file read must satisfy: states at consecutive steps, usable shapes, lanelet bounds.
void expect_consistent(const scenario& s, const std::string& name) {
  EXPECT_TRUE(s.version == "2018b" || s.version == "2020a") << name;
  EXPECT_GT(s.time_step, 0.0) << name;
  for (const obstacle& o : s.obstacles) {
    ASSERT_FALSE(o.states.empty()) << name << " obstacle " << o.id;
    for (std::size_t i = 1; i < o.states.size(); ++i) EXPECT_EQ(o.states[i].step, o.states[0].step + static_cast<std::int64_t>(i));
    EXPECT_FALSE(mm::footprint_error(o.shape)) << name << " obstacle " << o.id;
    EXPECT_FALSE(o.type.empty());
  }
  for (const lanelet& l : s.lanelets) {
    EXPECT_GE(l.left_bound.size(), 2U);
    EXPECT_GE(l.right_bound.size(), 2U);
  }
}

TEST(commonroad_reader, reads_the_obstacles_shapes_and_states_of_a_2020a_file) {
  const scenario s = read_scenario(data_file("ZAM_Tutorial-1_2_T-1.xml"));
  expect_consistent(s, "ZAM_Tutorial");
  EXPECT_EQ(s.version, "2020a");
  EXPECT_EQ(s.benchmark_id, "ZAM_Tutorial-1_1_T-1");  // not the file name (README)
  EXPECT_EQ(s.time_step, 0.1);
  EXPECT_EQ(s.lanelets.size(), 3U);
  ASSERT_EQ(s.obstacles.size(), 3U);

  const obstacle& parked = s.obstacles[0];
  EXPECT_EQ(parked.id, 43U);
  EXPECT_EQ(parked.role, obstacle_role::static_obstacle);
  EXPECT_EQ(parked.type, "parkedVehicle");
  // Its rectangle gives orientation 0 and centre (0, 0): no offset, so still a rectangle.
  ASSERT_TRUE(std::holds_alternative<mm::rectangle>(parked.shape));
  EXPECT_EQ(std::get<mm::rectangle>(parked.shape).length, 4.5);
  EXPECT_EQ(std::get<mm::rectangle>(parked.shape).width, 2.0);
  ASSERT_EQ(parked.states.size(), 1U);
  EXPECT_EQ(parked.states[0].position, (mm::vec2{30.0, 3.5}));
  EXPECT_EQ(parked.states[0].orientation, 0.02);
  EXPECT_EQ(parked.states[0].velocity, 0.0);  // not given for the static obstacle

  const obstacle& car = s.obstacles[1];
  EXPECT_EQ(car.id, 42U);
  EXPECT_EQ(car.role, obstacle_role::dynamic_obstacle);
  EXPECT_EQ(car.type, "car");
  ASSERT_EQ(car.states.size(), 41U);
  EXPECT_EQ(car.states[0].step, 0);
  EXPECT_EQ(car.states[0].position, (mm::vec2{2.25, 3.5}));
  EXPECT_EQ(car.states[0].velocity, 23.0);
  EXPECT_EQ(car.states[0].acceleration, 0.0);
  EXPECT_FALSE(car.states[0].yaw_rate);
  EXPECT_EQ(car.states[1].step, 1);
  EXPECT_EQ(car.states[1].position, (mm::vec2{4.5499419, 3.4939953}));
  EXPECT_EQ(car.states[1].orientation, -0.010443472);
  EXPECT_EQ(car.states[1].velocity, 23.000007);
  EXPECT_EQ(car.states.back().step, 40);

  const obstacle& ahead = s.obstacles[2];
  EXPECT_EQ(ahead.id, 44U);
  ASSERT_TRUE(std::holds_alternative<mm::rectangle>(ahead.shape));
  EXPECT_EQ(std::get<mm::rectangle>(ahead.shape).length, 4.3);
  EXPECT_EQ(ahead.states[0].position, (mm::vec2{50.0, 0.0}));
  EXPECT_FALSE(ahead.states[0].acceleration);  // this file omits it here

  ASSERT_EQ(s.planning_problems.size(), 1U);
  EXPECT_EQ(s.planning_problems[0].id, 100U);
  EXPECT_EQ(s.planning_problems[0].initial.position, (mm::vec2{15.0, 0.0}));
  EXPECT_EQ(s.planning_problems[0].initial.velocity, 22.0);
  EXPECT_EQ(s.planning_problems[0].initial.yaw_rate, 0.0);
}

TEST(commonroad_reader, reads_a_pedestrian_disc_and_an_obstacle_with_the_planning_problems_id) {
  const scenario s = read_scenario(data_file("OSC_PedestrianCollision-1_1_T-1.xml"));
  expect_consistent(s, "OSC_PedestrianCollision");
  EXPECT_EQ(s.benchmark_id, "ZAM_OpenDrive-1");
  EXPECT_EQ(s.lanelets.size(), 24U);
  ASSERT_EQ(s.obstacles.size(), 2U);
  const obstacle& pedestrian = find_obstacle(s, 35);
  EXPECT_EQ(pedestrian.type, "pedestrian");
  ASSERT_TRUE(std::holds_alternative<mm::disc>(pedestrian.shape));
  EXPECT_EQ(std::get<mm::disc>(pedestrian.shape).radius, 0.30000001192092896);
  EXPECT_EQ(pedestrian.states[0].position, (mm::vec2{35.6783, -23.5704}));
  EXPECT_EQ(pedestrian.states[0].orientation, 1.7984);
  EXPECT_EQ(pedestrian.states.back().step, 92);

  const obstacle& car = find_obstacle(s, 34);
  EXPECT_EQ(car.type, "car");
  EXPECT_EQ(std::get<mm::rectangle>(car.shape).length, 5.039999961853027);
  EXPECT_EQ(car.states[0].yaw_rate, 0.0144);
  ASSERT_EQ(s.planning_problems.size(), 1U);
  EXPECT_EQ(s.planning_problems[0].id, 34U);  // the same id as the car: allowed
  EXPECT_EQ(s.planning_problems[0].initial.position, car.states[0].position);
  EXPECT_EQ(s.planning_problems[0].initial.velocity, 9.0);
  EXPECT_EQ(s.planning_problems[0].initial.orientation, 1.7762);
}

TEST(commonroad_reader, reads_the_obstacles_of_a_2018b_file_by_their_role) {
  const scenario s = read_scenario(data_file("USA_Lanker-1_1_T-1.xml"));
  expect_consistent(s, "USA_Lanker-1_1");
  EXPECT_EQ(s.version, "2018b");
  EXPECT_EQ(s.benchmark_id, "USA_Lanker-1_1_T-1");
  EXPECT_EQ(s.time_step, 0.1);
  EXPECT_EQ(s.lanelets.size(), 91U);
  EXPECT_EQ(s.lanelets[0].id, 3419U);
  EXPECT_EQ(s.lanelets[0].left_bound[0], (mm::vec2{29.1793, 70.0118}));
  EXPECT_EQ(s.lanelets[0].right_bound[2], (mm::vec2{23.0181, 64.4496}));
  std::size_t links = 0;
  for (const lanelet& l : s.lanelets) links += l.predecessors.size() + l.successors.size();
  EXPECT_EQ(links, 2U * 84U) << "each of the file's 84 successor links has its predecessor link";
  ASSERT_EQ(s.obstacles.size(), 24U);
  for (const obstacle& o : s.obstacles) {
    EXPECT_EQ(o.role, obstacle_role::dynamic_obstacle);
    EXPECT_EQ(o.type, "car");
  }
  const obstacle& first = s.obstacles[0];
  EXPECT_EQ(first.id, 1213U);
  EXPECT_EQ(std::get<mm::rectangle>(first.shape).length, 3.1699);
  EXPECT_EQ(std::get<mm::rectangle>(first.shape).width, 2.0726);
  EXPECT_EQ(first.states[0].position, (mm::vec2{6.6928, 14.2381}));
  EXPECT_EQ(first.states[0].orientation, 1.1332);
  EXPECT_EQ(first.states[0].velocity, 9.6378);
  EXPECT_EQ(first.states[0].acceleration, 0.31699);
  EXPECT_EQ(first.states[1].position, (mm::vec2{7.1255, 15.1052}));
  EXPECT_EQ(first.states[1].orientation, 1.0983);
  EXPECT_EQ(find_obstacle(s, 1230).states.size(), 9U);  // leaves early, at step 8
  ASSERT_EQ(s.planning_problems.size(), 1U);
  EXPECT_EQ(s.planning_problems[0].id, 1215U);
  EXPECT_EQ(s.planning_problems[0].initial.velocity, 7.1171);
  EXPECT_EQ(s.planning_problems[0].initial.yaw_rate, -0.005041);
}

TEST(commonroad_reader, reads_an_intersection_file) {
  const scenario s = read_scenario(data_file("ZAM_Intersection-1_1_T-1.xml"));
  expect_consistent(s, "ZAM_Intersection");
  EXPECT_EQ(s.lanelets.size(), 20U);
  ASSERT_EQ(s.obstacles.size(), 2U);
  EXPECT_EQ(s.obstacles[0].id, 31U);
  EXPECT_EQ(s.obstacles[0].states[0].velocity, 15.7864);
  EXPECT_EQ(s.obstacles[0].states[0].orientation, -1.5707);
  EXPECT_EQ(s.obstacles[0].states.size(), 81U);
  EXPECT_EQ(s.obstacles[1].states.size(), 60U);
  ASSERT_EQ(s.planning_problems.size(), 1U);
  EXPECT_EQ(s.planning_problems[0].id, 37U);
  EXPECT_EQ(s.planning_problems[0].initial.position, (mm::vec2{44.5, -20.0}));
}

TEST(commonroad_reader, reads_every_file_of_the_data_folder) {
  const auto files = xml_files(source_dir() / "data/commonroad");
  EXPECT_GE(files.size(), 4U);
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    const scenario s = read_scenario(file);
    expect_consistent(s, file.filename().string());
    EXPECT_FALSE(s.planning_problems.empty());
  }
}

struct collection_file {
  const char* name;
  const char* version;
  double time_step;
  std::size_t lanelets, obstacles, planning_problems;
  std::int64_t last_step;
  std::size_t appearing_late;  ///< obstacles whose first step is > 0
};

// Counted from the files (they agree with README.md's table).
const collection_file collection[] = {
    {"BEL_Putte-8_2_T-1.xml", "2020a", 0.1, 41, 10, 1, 36, 0},
    {"C-DEU_AachenBendplatz-1_141360_T-1439.xml", "2020a", 0.2, 26, 14, 3, 79, 7},
    {"DEU_AAH1-2_76900_T-7049.xml", "2020a", 0.04, 26, 10, 1, 149, 2},
    {"DEU_AachenFrankenburg-1_2120_T-39.xml", "2020a", 0.2, 48, 29, 1, 19, 2},
    {"DEU_Flensburg-10_1_T-1.xml", "2020a", 0.1, 26, 27, 1, 100, 0},
    {"DEU_Muehlhausen-11_1_T-1.xml", "2020a", 0.1, 34, 10, 1, 36, 0},
    {"OSC_CutIn-1_2_T-1.xml", "2020a", 0.1, 2, 2, 1, 99, 0},
    {"OSC_PedestrianCollision-1_1_T-1.xml", "2020a", 0.1, 24, 2, 1, 92, 0},
    {"USA_Lanker-1_1_T-1.xml", "2018b", 0.1, 91, 24, 1, 40, 0},
    {"USA_Lanker-1_3_T-1.xml", "2020a", 0.1, 95, 36, 1, 40, 0},
    {"USA_Peach-4_8_T-1.xml", "2020a", 0.1, 79, 9, 1, 60, 0},
    {"USA_US101-4_1_T-1.xml", "2020a", 0.1, 12, 22, 1, 100, 0},
    {"USA_US101-5_1_T-1.xml", "2020a", 0.1, 5, 25, 1, 100, 0},
    {"ZAM_Intersection-1_1_T-1.xml", "2020a", 0.1, 20, 2, 1, 80, 0},
    {"ZAM_Tjunction-1_97_T-1.xml", "2020a", 0.1, 12, 5, 1, 147, 0},
    {"ZAM_Tutorial-1_2_T-1.xml", "2020a", 0.1, 3, 3, 1, 40, 0},
};

TEST(commonroad_reader, reads_every_file_of_the_shared_collection) {
  const std::filesystem::path dir = source_dir() / "../shared/data/commonroad";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " is not there";
  const auto files = xml_files(dir);
  EXPECT_GE(files.size(), 16U);
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    const scenario s = read_scenario(file);
    expect_consistent(s, file.filename().string());
    for (const collection_file& c : collection) {
      if (file.filename() != c.name) continue;
      EXPECT_EQ(s.version, c.version);
      EXPECT_EQ(s.time_step, c.time_step);
      EXPECT_EQ(s.lanelets.size(), c.lanelets);
      EXPECT_EQ(s.obstacles.size(), c.obstacles);
      EXPECT_EQ(s.planning_problems.size(), c.planning_problems);
      std::int64_t last = 0;
      std::size_t late = 0;
      for (const obstacle& o : s.obstacles) {
        last = std::max(last, o.states.back().step);
        if (o.states[0].step > 0) ++late;
        // README: every dynamic obstacle has a recorded trajectory.
        if (o.role == obstacle_role::dynamic_obstacle) {
          EXPECT_GT(o.states.size(), 1U) << o.id;
        }
      }
      EXPECT_EQ(last, c.last_step);
      EXPECT_EQ(late, c.appearing_late);
    }
  }
}

// ---- small documents ------------------------------------------------------------------------

/// A 2020a document: line 1 the declaration, line 2 the root, `body` from line 3.
std::string document(const std::string& body, const std::string& root_attributes =
                                                   R"(timeStepSize="0.1" commonRoadVersion="2020a" benchmarkID="T-1")") {
  return "<?xml version='1.0' encoding='UTF-8'?>\n<commonRoad " + root_attributes + ">\n" + body + "</commonRoad>\n";
}

std::string exact(const char* name, const std::string& value) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about the chain of + here.
  std::string text = "<";
  text.append(name).append("><exact>").append(value).append("</exact></").append(name).append(">");
  return text;
}

/// A state's children in the usual order, one per line.
std::string state_children(double x, double y, std::int64_t step, const std::string& velocity = "1.0") {
  return "<position><point><x>" + std::to_string(x) + "</x><y>" + std::to_string(y) + "</y></point></position>\n" +
         exact("orientation", "0.5") + "\n" + exact("time", std::to_string(step)) + "\n" +
         (velocity.empty() ? "" : exact("velocity", velocity) + "\n");
}

std::string dynamic_obstacle(int id, const std::string& shape, int states, std::int64_t first_step = 0) {
  std::string out = "<dynamicObstacle id=\"" + std::to_string(id) + "\">\n<type>car</type>\n<shape>" + shape +
                    "</shape>\n<initialState>\n" + state_children(0, 0, first_step) + "</initialState>\n";
  if (states > 1) {
    out += "<trajectory>\n";
    for (int i = 1; i < states; ++i) out += "<state>\n" + state_children(i, 0, first_step + i) + "</state>\n";
    out += "</trajectory>\n";
  }
  return out + "</dynamicObstacle>\n";
}

const std::string car_rectangle = "<rectangle><length>4</length><width>2</width></rectangle>";

const std::string planning_problem_xml =
    "<planningProblem id=\"7\">\n<initialState>\n" + state_children(1, 2, 0, "3.5") +
    "</initialState>\n<goalState>" + exact("time", "10") + "</goalState>\n</planningProblem>\n";

TEST(commonroad_reader, finds_state_children_in_any_order_and_skips_unknown_ones) {
  const std::string text = document(R"(<location><geoNameId>1</geoNameId></location>
<lanelet id="1"><leftBound><point><x>0</x><y>3</y></point><point><x>10</x><y>3</y></point><lineMarking>solid</lineMarking></leftBound>
<rightBound><point><x>0</x><y>0</y></point><point><x>10</x><y>0</y></point></rightBound><laneletType>urban</laneletType></lanelet>
<trafficSign id="9"><trafficSignElement><trafficSignID>274</trafficSignID></trafficSignElement></trafficSign>
<dynamicObstacle id="5">
  <type>bicycle</type>
  <shape><circle><radius> 0.8 </radius></circle></shape>
  <initialState>
    <time><exact>3</exact></time>
    <velocity><exact>+2.5</exact></velocity>
    <orientation><exact>-6.12</exact></orientation>
    <position><point><y>-1e1</y><x>4.25</x></point></position>
    <slipAngle><exact>0.0</exact></slipAngle>
    <yawRate><exact>0.1</exact></yawRate>
  </initialState>
  <initialSignalState><time><exact>3</exact></time><indicatorLeft>false</indicatorLeft></initialSignalState>
  <trajectory>
    <state><time><exact>4</exact></time><acceleration><exact>-0.5</exact></acceleration><velocity><exact>2.4</exact></velocity>
      <orientation><exact>-6.1</exact></orientation><position><point><x>4.5</x><y>-10</y></point></position></state>
  </trajectory>
  <signalSeries><signalState><time><exact>4</exact></time></signalState></signalSeries>
</dynamicObstacle>
)" + planning_problem_xml);
  const scenario s = read_scenario_text(text, "order.xml");
  EXPECT_EQ(s.benchmark_id, "T-1");
  ASSERT_EQ(s.lanelets.size(), 1U);
  EXPECT_EQ(s.lanelets[0].left_bound[1], (mm::vec2{10.0, 3.0}));
  ASSERT_EQ(s.obstacles.size(), 1U);
  const obstacle& o = s.obstacles[0];
  EXPECT_EQ(o.type, "bicycle");
  ASSERT_TRUE(std::holds_alternative<mm::disc>(o.shape));
  EXPECT_EQ(std::get<mm::disc>(o.shape).radius, 0.8);
  ASSERT_EQ(o.states.size(), 2U);
  EXPECT_EQ(o.states[0].step, 3);
  EXPECT_EQ(o.states[0].position, (mm::vec2{4.25, -10.0}));
  EXPECT_EQ(o.states[0].orientation, -6.12);
  EXPECT_EQ(o.states[0].velocity, 2.5);
  EXPECT_EQ(o.states[0].yaw_rate, 0.1);
  EXPECT_FALSE(o.states[0].acceleration);
  EXPECT_EQ(o.states[1].step, 4);
  EXPECT_EQ(o.states[1].acceleration, -0.5);
  EXPECT_FALSE(o.states[1].yaw_rate);
  ASSERT_EQ(s.planning_problems.size(), 1U);
  EXPECT_EQ(s.planning_problems[0].initial.velocity, 3.5);
  EXPECT_EQ(s.planning_problems[0].initial.position, (mm::vec2{1.0, 2.0}));
}

TEST(commonroad_reader, reads_a_2018b_static_obstacle_without_velocity_or_trajectory_states_and_a_missing_benchmark_id) {
  const std::string text = document(R"(<obstacle id="3"><role>static</role><type>parkedVehicle</type>
<shape><rectangle><length>4</length><width>2</width></rectangle></shape>
<initialState><position><point><x>1</x><y>2</y></point></position><orientation><exact>0.3</exact></orientation><time><exact>0</exact></time></initialState>
<trajectory/>
</obstacle>
<obstacle id="4"><role>dynamic</role><type>car</type><shape>)" + car_rectangle + R"(</shape>
<initialState>)" + state_children(5, 5, 0) + R"(</initialState></obstacle>
)",
                                    R"(commonRoadVersion="2018b" timeStepSize="0.2")");
  const scenario s = read_scenario_text(text, "old.xml");
  EXPECT_EQ(s.version, "2018b");
  EXPECT_EQ(s.benchmark_id, "");
  EXPECT_EQ(s.time_step, 0.2);
  ASSERT_EQ(s.obstacles.size(), 2U);
  EXPECT_EQ(s.obstacles[0].role, obstacle_role::static_obstacle);
  EXPECT_EQ(s.obstacles[0].states[0].velocity, 0.0);
  EXPECT_EQ(s.obstacles[0].states[0].orientation, 0.3);
  EXPECT_EQ(s.obstacles[1].role, obstacle_role::dynamic_obstacle);
  EXPECT_EQ(s.obstacles[1].states.size(), 1U);  // a dynamic obstacle without trajectory
  EXPECT_TRUE(s.planning_problems.empty());
}

const mm::convex_polygon& polygon_of(const scenario& s) { return std::get<mm::convex_polygon>(s.obstacles.at(0).shape); }

TEST(commonroad_reader, turns_a_rectangle_with_an_offset_into_a_polygon_of_its_corners) {
  const double angle = std::numbers::pi / 2.0;
  const std::string shape = "<rectangle><length>4</length><width>2</width><orientation>" + std::to_string(angle) +
                            "</orientation><center><x>1</x><y>0.5</y></center></rectangle>";
  const scenario s = read_scenario_text(document(dynamic_obstacle(1, shape, 1)), "rect.xml");
  const auto& v = polygon_of(s).vertices;
  ASSERT_EQ(v.size(), 4U);
  // Turned a quarter left: 4 m along y, 2 m along x, about (1, 0.5).
  const std::vector<mm::vec2> expected = {{2.0, 2.5}, {0.0, 2.5}, {0.0, -1.5}, {2.0, -1.5}};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(v[i].x, expected[i].x, 1e-6) << i;
    EXPECT_NEAR(v[i].y, expected[i].y, 1e-6) << i;
  }
  EXPECT_FALSE(mm::footprint_error(s.obstacles[0].shape));

  const std::string centred_only = "<rectangle><length>4</length><width>2</width><center><x>-0.5</x><y>0</y></center></rectangle>";
  const scenario t = read_scenario_text(document(dynamic_obstacle(1, centred_only, 1)), "rect.xml");
  const auto& w = polygon_of(t).vertices;
  ASSERT_EQ(w.size(), 4U);
  EXPECT_EQ(w[0], (mm::vec2{1.5, -1.0}));
  EXPECT_EQ(w[2], (mm::vec2{-2.5, 1.0}));
}

TEST(commonroad_reader, turns_an_offset_circle_into_a_16_gon_that_contains_it) {
  const std::string shape = "<circle><radius>0.5</radius><center><x>0.3</x><y>-0.2</y></center></circle>";
  const scenario s = read_scenario_text(document(dynamic_obstacle(1, shape, 1)), "circle.xml");
  const auto& v = polygon_of(s).vertices;
  ASSERT_EQ(v.size(), 16U);
  EXPECT_FALSE(mm::footprint_error(s.obstacles[0].shape));
  const mm::vec2 centre{0.3, -0.2};
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_NEAR(mm::norm(v[i] - centre), 0.5 / std::cos(std::numbers::pi / 16.0), 1e-12);
    // Each edge touches the circle: its distance from the centre is the radius.
    const mm::vec2 a = v[i];
    const mm::vec2 b = v[(i + 1) % v.size()];
    EXPECT_NEAR(std::abs(mm::cross(b - a, centre - a)) / mm::norm(b - a), 0.5, 1e-12);
  }
}

TEST(commonroad_reader, reads_a_convex_polygon_without_its_closing_point) {
  const std::string shape = "<polygon><point><x>2</x><y>-1</y></point><point><x>2</x><y>1</y></point>"
                            "<point><x>-2</x><y>1</y></point><point><x>-2</x><y>-1</y></point>"
                            "<point><x>2</x><y>-1</y></point></polygon>";
  const scenario s = read_scenario_text(document(dynamic_obstacle(1, shape, 2)), "polygon.xml");
  const auto& v = polygon_of(s).vertices;
  ASSERT_EQ(v.size(), 4U);
  EXPECT_EQ(v[3], (mm::vec2{-2.0, -1.0}));
}

// ---- errors ---------------------------------------------------------------------------------

struct error_case {
  const char* what;
  std::string text;
  std::string marker;                 ///< the first line holding this text is the expected line
  std::vector<std::string> contains;  ///< the field path, the value and the expectation
};

[[maybe_unused]] void PrintTo(const error_case& c, std::ostream* os) { *os << c.what; }

/// `text` with every `from` replaced by `to`.
std::string replaced_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

int line_of(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// `text` up to the first `at`, marked there: a file cut short.
std::string cut_short(std::string text, const std::string& at) {
  text.resize(text.find(at));
  text.append("<!-- cut here -->");
  return text;
}

/// `text` with the first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

const std::string valid = document(dynamic_obstacle(35, car_rectangle, 5) + planning_problem_xml);

std::vector<error_case> error_cases() {
  const std::string trajectory_state_3_velocity = "<state>\n" + state_children(3, 0, 3);
  const auto in_state_3 = [&](const std::string& from, const std::string& to) {
    const std::size_t at = valid.find(trajectory_state_3_velocity);
    std::string text = valid;
    const std::size_t field = text.find(from, at);
    text.replace(field, from.size(), to);
    return text;
  };
  const std::string obstacle_43 = replaced(dynamic_obstacle(35, car_rectangle, 1), "id=\"35\"", "id=\"43\"");
  return {
      {"a word as a number", in_state_3("<velocity><exact>1.0<", "<velocity><exact>abc<"), "<exact>abc",
       {"dynamicObstacle 35 / trajectory / state 3 / velocity: 'abc': expected a finite number in <exact>"}},
      {"nan", in_state_3("<orientation><exact>0.5<", "<orientation><exact>nan<"), "<exact>nan",
       {"dynamicObstacle 35 / trajectory / state 3 / orientation", "'nan'", "finite number"}},
      {"inf", in_state_3("<orientation><exact>0.5<", "<orientation><exact>-inf<"), "<exact>-inf", {"'-inf'", "finite number"}},
      {"an out of range number", in_state_3("<velocity><exact>1.0<", "<velocity><exact>1e400<"), "1e400", {"'1e400'"}},
      {"trailing garbage", in_state_3("<x>3.000000</x>", "<x>3.0m</x>"), "3.0m",
       {"dynamicObstacle 35 / trajectory / state 3 / position / point / x", "'3.0m'", "a finite number of metres"}},
      {"a missing coordinate", in_state_3("<x>3.000000</x>", ""), "<point><y>0.000000</y></point>", {"point / x: missing"}},
      {"a missing velocity of a dynamic obstacle", in_state_3("<velocity><exact>1.0</exact></velocity>", ""),
       "<state>\n<position><point><x>3.0", {"dynamicObstacle 35 / trajectory / state 3 / velocity: missing", "<exact>"}},
      {"an interval instead of an exact value",
       in_state_3("<velocity><exact>1.0</exact>", "<velocity><intervalStart>1</intervalStart><intervalEnd>2</intervalEnd>"),
       "<intervalStart>1", {"state 3 / velocity: an interval (<intervalStart>)", "expected <exact>"}},
      {"a step gap", in_state_3("<time><exact>3<", "<time><exact>4<"), "<time><exact>4<",
       {"dynamicObstacle 35 / trajectory / state 3 / time: '4': expected step 3", "initial state's step 0"}},
      {"a step that is not an integer", in_state_3("<time><exact>3<", "<time><exact>3.0<"), "<exact>3.0",
       {"state 3 / time: '3.0'", "integer step"}},
      {"a negative step", replaced(valid, "<time><exact>0<", "<time><exact>-1<"), "<exact>-1", {"initialState / time: '-1'"}},
      {"a huge step", replaced(valid, "<time><exact>0<", "<time><exact>99999999999999999999<"), "<exact>9999",
       {"initialState / time: '99999999999999999999'"}},
      {"a duplicate obstacle id",
       replaced(valid, "<planningProblem", obstacle_43 + replaced_all(dynamic_obstacle(35, car_rectangle, 1), "dynamicObstacle", "staticObstacle") + "<planningProblem"),
       "<staticObstacle id=\"35\"", {"staticObstacle 35 / id: '35': expected an id no other obstacle has (dynamicObstacle 35 at line 3 has it)"}},
      {"a duplicate planning problem id", replaced(valid, "</commonRoad>", planning_problem_xml + "</commonRoad>"),
       "<planningProblem id=\"7\">\n<initialState>\n<position><point><x>1.000000</x><y>2.000000</y></point></position>\n<orientation><exact>0.5</exact></orientation>\n<time><exact>0</exact></time>\n<velocity><exact>3.5</exact></velocity>\n</initialState>\n<goalState><time><exact>10</exact></time></goalState>\n</planningProblem>\n</commonRoad>",
       {"planningProblem 7 / id: '7'", "no other planning problem"}},
      {"an occupancy set", replaced(valid, "<trajectory>", "<occupancySet><occupancy/></occupancySet>\n<trajectory>"), "<occupancySet>",
       {"dynamicObstacle 35 / occupancySet: set-based occupancies are not supported"}},
      {"an unsupported version", replaced(valid, "2020a", "2019b"), "<commonRoad",
       {"commonRoad / commonRoadVersion: '2019b': expected 2018b or 2020a"}},
      {"a missing version", replaced(valid, "commonRoadVersion=\"2020a\"", ""), "<commonRoad", {"commonRoadVersion: missing"}},
      {"a zero time step", replaced(valid, "timeStepSize=\"0.1\"", "timeStepSize=\"0\""), "<commonRoad", {"timeStepSize: '0'", "positive"}},
      {"a nan time step", replaced(valid, "timeStepSize=\"0.1\"", "timeStepSize=\"NaN\""), "<commonRoad", {"timeStepSize: 'NaN'"}},
      {"another document element", "<?xml version='1.0'?>\n\n<scenario/>\n", "<scenario", {"document element: <scenario>"}},
      {"malformed XML", replaced(valid, "</trajectory>", "</trajectroy>"), "</trajectroy>", {"not well-formed XML", "mismatch"}},
      {"an empty text", "", "", {"not well-formed XML", "the file is empty"}},
      {"a file cut short", cut_short(valid, "</trajectory>"), "<!-- cut here -->",
       {"not well-formed XML: the file ends inside the document", "cut short"}},
      {"a position given as a shape",
       replaced(valid, "<position><point><x>0.000000</x><y>0.000000</y></point></position>",
                "<position><rectangle><length>1</length><width>1</width></rectangle></position>"),
       "<position><rectangle>", {"dynamicObstacle 35 / initialState / position: <rectangle>", "only points are supported"}},
      {"a shape group", replaced(valid, car_rectangle, "<shapeGroup>" + car_rectangle + "</shapeGroup>"), "<shapeGroup>",
       {"dynamicObstacle 35 / shape: unsupported shape <shapeGroup>"}},
      {"two shapes", replaced(valid, car_rectangle, car_rectangle + "\n<circle><radius>1</radius></circle>"), "<circle>",
       {"dynamicObstacle 35 / shape: several shapes (<rectangle> and <circle>)"}},
      {"no shape", replaced(valid, "<shape>" + car_rectangle + "</shape>", ""), "<dynamicObstacle", {"dynamicObstacle 35 / shape: missing"}},
      {"a non-convex polygon",
       replaced(valid, car_rectangle,
                "<polygon><point><x>2</x><y>0</y></point><point><x>0</x><y>0.5</y></point><point><x>-2</x><y>0</y></point>"
                "<point><x>0</x><y>2</y></point></polygon>"),
       "<polygon>", {"dynamicObstacle 35 / shape / polygon", "not convex"}},
      {"a negative length", replaced(valid, "<length>4</length>", "\n<length>-4</length>"), "<length>-4",
       {"shape / rectangle / length: '-4': expected a positive finite number of metres"}},
      {"a zero radius", replaced(valid, car_rectangle, "<circle><radius>0</radius></circle>"), "<circle>", {"shape / circle / radius: '0'"}},
      {"a zero id", replaced(valid, "id=\"35\"", "id=\"0\""), "<dynamicObstacle", {"dynamicObstacle / id: '0': expected a positive integer id"}},
      {"an id beyond 32 bits", replaced(valid, "id=\"35\"", "id=\"4294967296\""), "<dynamicObstacle", {"'4294967296'"}},
      {"a missing id", replaced(valid, " id=\"35\"", ""), "<dynamicObstacle", {"dynamicObstacle / id: missing"}},
      {"a negative lanelet id",
       replaced(valid, "<dynamicObstacle", "<lanelet id=\"-1\">\n<leftBound/><rightBound/></lanelet>\n<dynamicObstacle"),
       "<lanelet", {"lanelet / id: '-1': expected a non-negative integer id"}},
      {"a lanelet with one point",
       replaced(valid, "<dynamicObstacle", "<lanelet id=\"2\">\n<leftBound><point><x>0</x><y>0</y></point></leftBound>\n"
                                          "<rightBound><point><x>0</x><y>0</y></point><point><x>1</x><y>0</y></point></rightBound></lanelet>\n<dynamicObstacle"),
       "<leftBound>", {"lanelet 2 / leftBound: 1 point(s): expected a polyline of at least 2 <point>s"}},
      {"a link that is no lanelet id",
       replaced(valid, "<dynamicObstacle", "<lanelet id=\"2\">\n<leftBound><point><x>0</x><y>0</y></point><point><x>1</x><y>0</y></point></leftBound>\n"
                                          "<rightBound><point><x>0</x><y>-1</y></point><point><x>1</x><y>-1</y></point></rightBound>\n"
                                          "<successor ref=\"next\"/></lanelet>\n<dynamicObstacle"),
       "<successor", {"lanelet 2 / successor / ref: 'next': expected a lanelet id"}},
      {"a lanelet without right bound",
       replaced(valid, "<dynamicObstacle", "<lanelet id=\"2\">\n<leftBound><point><x>0</x><y>0</y></point><point><x>1</x><y>0</y></point></leftBound></lanelet>\n<dynamicObstacle"),
       "<lanelet", {"lanelet 2 / rightBound: missing"}},
      {"a lanelet point that is not a number",
       replaced(valid, "<dynamicObstacle", "<lanelet id=\"2\">\n<leftBound><point><x>0</x><y>0</y></point>\n<point><x>1</x><y>zero</y></point></leftBound></lanelet>\n<dynamicObstacle"),
       "<y>zero", {"lanelet 2 / leftBound / point 2 / y: 'zero'"}},
      {"a static obstacle with a trajectory", replaced_all(valid, "dynamicObstacle", "staticObstacle"), "<trajectory>",
       {"staticObstacle 35 / trajectory"}},
      {"an unknown 2018b role", replaced(replaced_all(valid, "dynamicObstacle", "obstacle"), "<type>", "<role>moving</role>\n<type>"),
       "<role>", {"obstacle 35 / role: 'moving': expected dynamic or static"}},
      {"a missing planning problem velocity", replaced(valid, "<velocity><exact>3.5</exact></velocity>", ""),
       "<initialState>\n<position><point><x>1.0", {"planningProblem 7 / initialState / velocity: missing"}},
      {"a missing orientation", replaced(valid, "<orientation><exact>0.5</exact></orientation>", ""), "<initialState>",
       {"dynamicObstacle 35 / initialState / orientation: missing"}},
      {"a missing type", replaced(valid, "<type>car</type>", ""), "<dynamicObstacle", {"dynamicObstacle 35 / type: missing"}},
      {"control bytes in a value", in_state_3("<velocity><exact>1.0<", std::string("<velocity><exact>1\x01<")), "<exact>1\x01",
       {"'1\\x01'"}},
  };
}

class commonroad_reader_errors : public ::testing::TestWithParam<error_case> {};

TEST_P(commonroad_reader_errors, the_message_names_the_source_line_field_value_and_expectation) {
  const error_case& c = GetParam();
  const int line = line_of(c.text, c.marker);
  ASSERT_GT(line, 0) << "marker not found: " << c.marker;
  try {
    read_scenario_text(c.text, "case.xml");
    FAIL() << c.what << ": no error for\n" << c.text;
  } catch (const read_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("case.xml:" + std::to_string(line) + ": ", 0), 0U) << message;
    for (const std::string& piece : c.contains) EXPECT_NE(message.find(piece), std::string::npos) << piece << "\n in: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(every_error, commonroad_reader_errors, ::testing::ValuesIn(error_cases()));

TEST(commonroad_reader, the_valid_base_document_of_the_error_cases_reads) {
  const scenario s = read_scenario_text(valid, "case.xml");
  ASSERT_EQ(s.obstacles.size(), 1U);
  EXPECT_EQ(s.obstacles[0].states.size(), 5U);
  EXPECT_EQ(s.planning_problems.size(), 1U);
}

TEST(commonroad_reader, a_missing_file_or_a_directory_is_an_error_naming_it_and_why) {
  const std::filesystem::path missing = source_dir() / "data/commonroad/no_such_file.xml";
  try {
    read_scenario(missing);
    FAIL() << "no error";
  } catch (const read_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string() + ": cannot open the file: No such file or directory"),
              std::string::npos)
        << e.what();
  }
  const std::filesystem::path folder = source_dir() / "data/commonroad";
  try {
    read_scenario(folder);
    FAIL() << "no error";
  } catch (const read_error& e) {
    EXPECT_NE(std::string(e.what()).find(folder.string() + ": is a directory"), std::string::npos) << e.what();
  }
}

TEST(commonroad_reader, an_error_in_a_real_file_names_the_file_and_its_line) {
  const std::filesystem::path file = data_file("ZAM_Tutorial-1_2_T-1.xml");
  const std::string text = file_text(file);
  const std::string broken = replaced(text, "<exact>23.000007</exact>", "<exact>fast</exact>");
  try {
    read_scenario_text(broken, file.string());
    FAIL() << "no error";
  } catch (const read_error& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ":" + std::to_string(line_of(broken, "<exact>fast")) +
                                         ": dynamicObstacle 42 / trajectory / state 1 / velocity: 'fast': "
                                         "expected a finite number in <exact>");
  }
}

TEST(commonroad_reader, cut_or_damaged_files_give_errors_and_nothing_worse) {
  const std::string text = file_text(data_file("ZAM_Tutorial-1_2_T-1.xml"));
  ASSERT_FALSE(text.empty());
  std::size_t errors = 0;
  for (std::size_t cut = 0; cut < text.size(); cut += 1009) {
    try {
      read_scenario_text(text.substr(0, cut), "cut.xml");
    } catch (const read_error&) {
      ++errors;
    }
  }
  EXPECT_EQ(errors, (text.size() + 1008) / 1009);  // a cut file is never complete
  for (std::size_t at = 7; at < text.size(); at += 613) {
    for (const char c : {'<', '>', 'x', '\0', '-', '"'}) {
      std::string damaged = text;
      damaged[at] = c;
      try {
        read_scenario_text(damaged, "damaged.xml");
      } catch (const read_error&) {
      }
    }
  }
}

}  // namespace
