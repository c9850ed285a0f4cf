// Writing CommonRoad files: every file read, written and read again is the same scenario, bit for bit.
#include "mm/commonroad/writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/commonroad/reader.hpp"

#include <pugixml.hpp>

namespace {

using namespace mm::commonroad;

std::filesystem::path source_dir() {
  const char* root = std::getenv("MM_SOURCE_DIR");
  return root ? std::filesystem::path(root) : std::filesystem::path(".");
}

std::vector<std::filesystem::path> xml_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".xml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void expect_reads_back(const std::filesystem::path& file) {
  SCOPED_TRACE(file.string());
  const scenario s = read_scenario(file);
  const std::string text = scenario_xml(s);
  const scenario back = read_scenario_text(text, "written");
  EXPECT_EQ(back.version, "2020a");
  EXPECT_TRUE(back == as_written(s));
  EXPECT_EQ(scenario_xml(back), text);
}

TEST(commonroad_writer, every_file_of_the_data_folder_and_the_seeds_reads_back_bit_for_bit) {
  std::vector<std::filesystem::path> files = xml_files(source_dir() / "data/commonroad");
  EXPECT_GE(files.size(), 4U);
  for (const auto& f : xml_files(source_dir() / "fuzz/commonroad_seeds")) files.push_back(f);
  for (const auto& file : files) expect_reads_back(file);
}

TEST(commonroad_writer, every_file_of_the_shared_collection_reads_back_bit_for_bit) {
  const auto files = xml_files(source_dir() / "../shared/data/commonroad");
  if (files.empty()) GTEST_SKIP() << "the shared collection is not there";
  for (const auto& file : files) expect_reads_back(file);
}

TEST(commonroad_writer, shapes_optional_values_and_goals_are_written_as_the_format_has_them) {
  scenario s;
  s.benchmark_id = "ZAM_Written-1_1_T-1";
  s.time_step = 0.04;
  s.lanelets.push_back({7, {{0.0, 1.75}, {50.0, 1.75}}, {{0.0, -1.75}, {50.0, -1.75}}, {}, {}});
  obstacle car{3, obstacle_role::dynamic_obstacle, "car", mm::rectangle{4.4, 1.9}, {}};
  car.states.push_back({2, {1.0 / 3.0, 0.0}, 6.5, 10.0, 0.01, -0.5});
  car.states.push_back({3, {0.7333333333333333, 0.0}, 6.5, 9.98, std::nullopt, std::nullopt});
  obstacle walker{4, obstacle_role::dynamic_obstacle, "pedestrian", mm::disc{0.3}, {{0, {20.0, 5.0}, -1.5, 1.2, std::nullopt, std::nullopt}}};
  obstacle cone{9, obstacle_role::static_obstacle, "unknown",
                mm::convex_polygon{{{0.3, 0.0}, {0.0, 0.3}, {-0.3, 0.0}, {0.0, -0.3}}}, {{0, {30.0, 0.0}, 0.0, 0.0, std::nullopt, std::nullopt}}};
  s.obstacles = {car, walker, cone};
  s.planning_problems.push_back({12, {0, {-20.0, 0.0}, 0.0, 13.9, std::nullopt, std::nullopt}});
  const std::string text = scenario_xml(s);
  EXPECT_NE(text.find("<circle>"), std::string::npos) << text;
  EXPECT_NE(text.find("<polygon>"), std::string::npos) << text;
  EXPECT_NE(text.find("<x>0.3333333333333333</x>"), std::string::npos) << text;
  EXPECT_NE(text.find("<yawRate>"), std::string::npos) << text;
  EXPECT_NE(text.find("<intervalStart>0</intervalStart>"), std::string::npos) << text;
  EXPECT_NE(text.find("<intervalEnd>3</intervalEnd>"), std::string::npos) << "until the last recorded step:\n" << text;
  const std::size_t static_start = text.find("<staticObstacle");
  const std::size_t static_end = text.find("</staticObstacle>");
  ASSERT_NE(static_end, std::string::npos) << text;
  EXPECT_EQ(text.substr(static_start, static_end - static_start).find("<velocity>"), std::string::npos)
      << "a static obstacle at rest has no velocity:\n"
      << text;
  const scenario back = read_scenario_text(text, "written");
  EXPECT_TRUE(back == as_written(s));
  EXPECT_EQ(back.date, undated);
  ASSERT_EQ(back.obstacles.size(), 3U);
  EXPECT_EQ(back.obstacles[0].id, 9U) << "the static obstacle first, as the schema orders them";
  EXPECT_EQ(back.obstacles[1].id, 3U);
  EXPECT_EQ(back.planning_problems[0].initial.yaw_rate, 0.0) << "the schema requires a yaw rate";
}

/// The names of `node`'s element children, in order.
std::vector<std::string> child_names(pugi::xml_node node) {
  std::vector<std::string> names;
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_element) names.emplace_back(c.name());
  }
  return names;
}

/// Every text of an element under `node` (numbers, ids, types).
void collect_texts(pugi::xml_node node, std::vector<std::string>& texts) {
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_pcdata) texts.emplace_back(c.value());
    collect_texts(c, texts);
  }
}

TEST(commonroad_writer, a_written_file_has_what_the_2020a_schema_requires) {
  scenario s = read_scenario(source_dir() / "data/commonroad/ZAM_Tutorial-1_2_T-1.xml");
  ASSERT_FALSE(s.obstacles.empty());
  // Numbers that std::to_chars' shortest form writes with an exponent.
  s.obstacles.front().states.front().velocity = 1e-05;
  s.obstacles.front().states.front().position.x = 1.5e20;
  s.obstacles.front().states.front().orientation = -2.5e-300;
  s.obstacles.push_back({99, obstacle_role::static_obstacle, "parkedVehicle", mm::rectangle{4.5, 2.0},
                         {{0, {10.0, 3.0}, 0.0, 0.0, std::nullopt, std::nullopt}}});
  const std::string text = scenario_xml(s);
  pugi::xml_document document;
  ASSERT_TRUE(document.load_string(text.c_str()));
  const pugi::xml_node root = document.document_element();
  for (const char* attribute : {"commonRoadVersion", "benchmarkID", "date", "author", "affiliation", "source", "timeStepSize"}) {
    EXPECT_TRUE(root.attribute(attribute)) << attribute;
  }
  EXPECT_EQ(std::string(root.attribute("date").value()), s.date) << "a read file's date is kept";
  // The root's children in the schema's order: location, scenarioTags, lanelets, static obstacles,
  // dynamic obstacles, planning problems.
  const std::vector<std::string> order = {"location", "scenarioTags", "lanelet", "staticObstacle", "dynamicObstacle",
                                          "planningProblem"};
  std::size_t at = 0;
  for (const std::string& name : child_names(root)) {
    const auto place = std::find(order.begin(), order.end(), name);
    ASSERT_NE(place, order.end()) << name;
    const auto index = static_cast<std::size_t>(place - order.begin());
    EXPECT_GE(index, at) << name << " after " << order[at];
    at = std::max(at, index);
  }
  EXPECT_EQ(child_names(root.child("location")), (std::vector<std::string>{"geoNameId", "gpsLatitude", "gpsLongitude"}));
  for (pugi::xml_node l = root.child("lanelet"); l; l = l.next_sibling("lanelet")) {
    EXPECT_EQ(child_names(l), (std::vector<std::string>{"leftBound", "rightBound", "laneletType"})) << "lanelet " << l.attribute("id").value();
  }
  const pugi::xml_node problem = root.child("planningProblem");
  ASSERT_TRUE(problem);
  std::vector<std::string> initial = child_names(problem.child("initialState"));
  std::sort(initial.begin(), initial.end());
  for (const char* element : {"orientation", "position", "slipAngle", "time", "velocity", "yawRate"}) {
    EXPECT_TRUE(std::binary_search(initial.begin(), initial.end(), std::string(element))) << element;
  }
  EXPECT_TRUE(problem.child("goalState").child("time")) << "a goal's time is required";
  // xs:decimal: digits, one point, a sign; no exponent, no inf or nan.
  std::vector<std::string> texts;
  collect_texts(root, texts);
  for (const std::string& t : texts) {
    if (t.empty() || !(std::isdigit(static_cast<unsigned char>(t.front())) || t.front() == '-')) continue;  // a type
    EXPECT_EQ(t.find_first_not_of("0123456789.-"), std::string::npos) << t;
  }
  EXPECT_NE(text.find("<x>150000000000000000000</x>"), std::string::npos);
  EXPECT_NE(text.find("<exact>0.00001</exact>"), std::string::npos);
  EXPECT_TRUE(read_scenario_text(text, "written") == as_written(s));
}

TEST(commonroad_writer, a_scenario_no_file_can_state_is_refused_and_an_unwritable_file_named) {
  scenario s = read_scenario(source_dir() / "data/commonroad/ZAM_Tutorial-1_2_T-1.xml");
  scenario gap = s;
  const auto moving = std::find_if(gap.obstacles.begin(), gap.obstacles.end(), [](const obstacle& o) { return o.states.size() > 2; });
  ASSERT_NE(moving, gap.obstacles.end());
  moving->states.back().step += 1;  // a trajectory that skips a step
  try {
    (void)scenario_xml(gap);
    ADD_FAILURE() << "a trajectory with a gap was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not one a CommonRoad file can state"), std::string::npos) << e.what();
  }
  scenario zero = s;
  zero.obstacles.front().id = 0;
  EXPECT_THROW((void)scenario_xml(zero), std::invalid_argument);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "mm_writer_no_dir" / "x.xml";
  try {
    write_scenario(s, file);
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const std::filesystem::filesystem_error& e) {
    EXPECT_EQ(e.path1(), file);
  }
}

}  // namespace
