// Every way a scenario file can be wrong, and what the message says: the file, the line (and
// column) of the offending YAML node, the field path, the value and what was expected.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "mm/scenario_file/loader.hpp"

namespace {

using namespace mm::scenario_file;

/// A valid scenario whose line `marker` (1-based) is replaced by `line` (or removed if empty).
const std::string base = R"(format: maneuvermap-scenario/1
name: base
parameters:
  a_kmh: 30
duration_s: 5
agents:
  - name: A
    kind: planning_vehicle
    path:
      start: {position_m: [0, 0], heading_deg: 0}
      segments:
        - straight_m: 100
    desired_speed_kmh: $a_kmh
  - name: B
    kind: scripted_vehicle
    path: {start: {position_m: [40, 40], heading_deg: -90}, segments: [{straight_m: 80}]}
    speed_kmh: 36
meet:
  - {agents: [A, B], conflict_point_m: [40, 0]}
)";

/// `base` with the lines numbered as in `base` (1-based) replaced (removed when empty); lines
/// past `keep` are dropped.
std::string with_lines(const std::vector<std::pair<int, std::string>>& replacements, int keep = 1000) {
  std::string out;
  int n = 1;
  std::size_t start = 0;
  while (start < base.size() && n <= keep) {
    const std::size_t end = base.find('\n', start);
    std::string line = base.substr(start, end - start) + "\n";
    for (const auto& [number, replacement] : replacements) {
      if (number == n) line = replacement.empty() ? "" : replacement + "\n";
    }
    out += line;
    start = end + 1;
    ++n;
  }
  return out;
}

std::string with_line(int number, const std::string& replacement) { return with_lines({{number, replacement}}); }

struct error_case {
  const char* what;
  std::string text;
  int line;                            ///< expected 1-based line, 0 for none
  std::string field;                   ///< expected field path
  std::vector<std::string> contains;   ///< expected pieces of the message (value, expectation)
};

// Names the case in test listings instead of dumping its bytes.
[[maybe_unused]] void PrintTo(const error_case& c, std::ostream* os) { *os << c.what; }

class scenario_file_errors : public ::testing::TestWithParam<error_case> {};

TEST_P(scenario_file_errors, the_message_names_the_file_line_field_value_and_expectation) {
  const error_case& c = GetParam();
  try {
    load_text(c.text, "case.yaml");
    FAIL() << c.what << ": no error for\n" << c.text;
  } catch (const scenario_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.source(), "case.yaml");
    EXPECT_EQ(e.line(), c.line) << message;
    EXPECT_EQ(e.field(), c.field) << message;
    if (c.line > 0) {
      EXPECT_EQ(message.rfind("case.yaml:" + std::to_string(c.line) + ":", 0), 0U) << message;
    }
    for (const std::string& piece : c.contains) EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
  }
}

const std::vector<error_case> cases{
    {"malformed YAML", with_line(10, "      start: {position_m: [0, 0], heading_deg: 0"), 11, "", {"malformed YAML"}},
    {"not a map", "- just\n- a list\n", 1, "", {"expected a map of top-level fields"}},
    {"missing format", with_line(1, ""), 1, "format", {"missing required field format"}},
    {"other version", with_line(1, "format: maneuvermap-scenario/2"), 1, "format",
     {"maneuvermap-scenario/2", "expected maneuvermap-scenario/1", "only that version"}},
    {"wrong format", with_line(1, "format: something"), 1, "format", {"= something", "expected maneuvermap-scenario/1"}},
    {"unknown top-level key with a suggestion", with_line(5, "duraton_s: 5"), 5, "duraton_s",
     {"unknown key", "did you mean duration_s?"}},
    {"unknown key in an agent", with_line(13, "    desird_speed_kmh: 30"), 13, "agents[0].desird_speed_kmh",
     {"unknown key", "did you mean desired_speed_kmh?"}},
    {"unknown key without a close match lists the keys", with_line(13, "    desired_speed_kmh: 30\n    colour: red"), 14,
     "agents[0].colour", {"unknown key; expected one of name, kind, path, ", ", desired_speed_kmh, desired_speed_mps, "}},
    {"unknown key that is part of known ones", with_line(13, "    desired_speed_kmh: 30\n    speed_kmh: 30"), 14,
     "agents[0].speed_kmh", {"unknown key; did you mean initial_speed_kmh or desired_speed_kmh?"}},
    {"missing required name", with_line(2, ""), 1, "name", {"missing required field name"}},
    {"missing desired speed", with_line(13, ""), 7, "agents[0]", {"missing required field desired_speed_kmh or desired_speed_mps"}},
    {"both units of one quantity", with_line(13, "    desired_speed_kmh: 30\n    desired_speed_mps: 8"), 14,
     "agents[0].desired_speed_mps", {"give either desired_speed_kmh or desired_speed_mps, not both"}},
    {"wrong type: text for a number", with_line(5, "duration_s: long"), 5, "duration_s", {"= long", "expected a positive number [s]"}},
    {"wrong type: map for a number", with_line(5, "duration_s: {a: 1}"), 5, "duration_s", {"= <a map>", "expected a positive number"}},
    {"out of range", with_line(5, "duration_s: -5"), 5, "duration_s", {"= -5", "expected a positive number [s]"}},
    {"not finite", with_line(5, "duration_s: inf"), 5, "duration_s", {"= inf", "expected a finite number"}},
    {"negative speed", with_line(17, "    speed_kmh: -36"), 17, "agents[1].speed_kmh", {"= -36", "expected a speed from 0 to 360 [km/h] (100 m/s)"}},
    {"a speed no road user has", with_line(13, "    desired_speed_mps: 1e27"), 13, "agents[0].desired_speed_mps",
     {"= 1e27", "expected a speed from 0 to 100 [m/s]"}},
    {"a static obstacle as thin as a sheet", with_line(17, "    speed_kmh: 36\n  - name: wall\n    kind: static_obstacle\n    vertices_m: [[0, 10], [20, 10], [20, 10.001]]"), 20,
     "agents[2].vertices_m", {"expected a polygon at least 0.05 m wide in every direction"}},
    {"a footprint of micrometres", with_line(17, "    speed_kmh: 36\n    footprint: {length_m: 4.5, width_m: 0.000002}"), 18,
     "agents[1].footprint.width_m", {"= 0.000002", "expected a size from 0.05 to 1000 [m]"}},
    {"a footprint a kilometre long", with_line(17, "    speed_kmh: 36\n    footprint: {length_m: 2000, width_m: 2}"), 18,
     "agents[1].footprint.length_m", {"= 2000", "expected a size from 0.05 to 1000 [m]"}},
    {"sensor noise beyond what the planner takes", with_line(5, "duration_s: 5\nsensing_noise: {speed_sd_kmh: 50}"), 6,
     "sensing_noise.speed_sd_kmh", {"= 50", "expected a standard deviation from 0 to 36 [km/h]"}},
    {"a path beyond what the planner takes",
     with_lines({{10, "      start: {position_m: [39999950, 0], heading_deg: 0}"}}, 17), 7, "agents[0] \"A\"",
     {"path: a segment from (39999950, 0) m of length 100 m reaches beyond ±4e+07 m"}},
    {"unknown parameter with a suggestion", with_line(13, "    desired_speed_kmh: $a_kmhh"), 13, "agents[0].desired_speed_kmh",
     {"$a_kmhh", "no parameter \"a_kmhh\"", "did you mean $a_kmh?"}},
    {"parameter in the wrong unit", with_line(13, "    desired_speed_mps: $a_kmh"), 13, "agents[0].desired_speed_mps",
     {"$a_kmh (= 30)", "parameter a_kmh is in \"_kmh\" units, the field desired_speed_mps in \"_mps\""}},
    {"parameter that refers to a parameter", with_line(4, "  a_kmh: $b_kmh"), 4, "parameters.a_kmh",
     {"parameters cannot refer to other parameters"}},
    {"bad parameter name", with_line(4, "  3d: 30"), 4, "parameters.3d", {"letters, digits and _"}},
    {"bad enum with a suggestion", with_line(13, "    desired_speed_kmh: 30\n    planner: {policy: adjj}"), 14,
     "agents[0].planner.policy", {"= adjj", "expected one of adj, const, robust (did you mean adj?)"}},
    {"bad kind", with_line(8, "    kind: car"), 8, "agents[0].kind",
     {"= car", "one of planning_vehicle, scripted_vehicle, pedestrian, static_obstacle"}},
    {"bad boolean", with_line(13, "    desired_speed_kmh: 30\n    avoidance: yes"), 14, "agents[0].avoidance",
     {"= yes", "expected true or false"}},
    {"negative time gap", with_line(13, "    desired_speed_kmh: 30\n    follower: {car_following: {time_gap_s: -1}}"), 14,
     "agents[0].follower.car_following.time_gap_s", {"= -1", "expected a number ≥ 0"}},
    {"unknown key in car following", with_line(13, "    desired_speed_kmh: 30\n    follower: {car_following: {time_gap: 1}}"), 14,
     "agents[0].follower.car_following.time_gap", {"unknown key", "did you mean time_gap_s?"}},
    {"a scripted vehicle that cannot brake", with_line(17, "    speed_kmh: 36\n    car_following: {max_deceleration_mps2: 0}"), 18,
     "agents[1].car_following.max_deceleration_mps2", {"= 0", "expected a positive number"}},
    {"unknown key in a scripted vehicle's car following",
     with_line(17, "    speed_kmh: 36\n    car_following: {time_gap_s: 1, reaction_time_s: 1}"), 18,
     "agents[1].car_following.reaction_time_s", {"unknown key"}},
    {"boolean parameter not 0 or 1", with_lines({{4, "  a_kmh: 30\n  flag: 2"}, {13, "    desired_speed_kmh: 30\n    avoidance: $flag"}}),
     15, "agents[0].avoidance", {"$flag (= 2)", "1 for true or 0 for false"}},
    {"parameter with a unit in a field without one", with_line(13, "    desired_speed_kmh: 30\n    avoidance: $a_kmh"), 14,
     "agents[0].avoidance", {"$a_kmh (= 30)", "parameter a_kmh is in \"_kmh\" units, the field avoidance in none"}},
    {"integer expected", with_line(13, "    desired_speed_kmh: 30\n    planning_period_steps: 1.5"), 14,
     "agents[0].planning_period_steps", {"= 1.5", "expected an integer"}},
    {"zero planning period", with_line(13, "    desired_speed_kmh: 30\n    planning_period_steps: 0"), 14,
     "agents[0].planning_period_steps", {"= 0", "from 1 to"}},
    {"duplicate agent name", with_line(14, "  - name: A"), 14, "agents[1].name", {"= A", "a name no other agent has"}},
    {"duplicate key", with_line(5, "duration_s: 5\nduration_s: 6"), 6, "duration_s", {"duplicate key"}},
    {"unknown key in the drivable area", with_line(5, "duration_s: 5\ndrivable_area: {polygon_m: [[0, 0], [1, 0], [0, 1]]}"), 6,
     "drivable_area.polygon_m", {"unknown key", "did you mean polygons_m?"}},
    {"a drivable area of the roads without roads", with_line(5, "duration_s: 5\ndrivable_area: {roads: true}"), 6,
     "drivable_area.roads", {"= true", "roads: in the file"}},
    {"a drivable area without a polygon", with_line(5, "duration_s: 5\ndrivable_area: {roads: false}"), 6,
     "drivable_area", {"expected roads: true", "roundabout: true", "polygons_m"}},
    {"a drivable area of the roundabout without one", with_line(5, "duration_s: 5\ndrivable_area: {roundabout: true}"), 6,
     "drivable_area.roundabout", {"= true", "a roundabout: block in the file"}},
    {"roundabout lanes too wide", with_line(5, "duration_s: 5\nroundabout: {connection_radius_m: 10, arms: {east: {angle_deg: 0}}}\n"
                                              "drivable_area: {roundabout: {lane_width_m: 20}}"), 7,
     "drivable_area.roundabout.lane_width_m", {"= 20", "a lane width below 20 m", "connection_radius_m"}},
    {"a roundabout beyond the paths' bound", with_line(5, "duration_s: 5\nroundabout: {radius_m: 1e20, arms: {east: {angle_deg: 0}}}"), 6,
     "roundabout", {"radius_m = 1e+20", "≤ 4e+07 m"}},
    {"an arm beyond the paths' bound", with_line(5, "duration_s: 5\nroundabout: {arms: {east: {angle_deg: 0, straight_length_m: 1e9}}}"), 6,
     "roundabout.arms.east", {"straight_length_m = 1e+09", "expected at most 39999910 m"}},
    {"unknown key in the roundabout's lanes", with_line(5, "duration_s: 5\nroundabout: {arms: {east: {angle_deg: 0}}}\n"
                                                        "drivable_area: {roundabout: {lane_width: 3}}"), 7,
     "drivable_area.roundabout.lane_width", {"unknown key", "did you mean lane_width_m?"}},
    {"a drivable polygon on one line", with_line(5, "duration_s: 5\ndrivable_area:\n  polygons_m:\n    - [[0, 0], [1, 1], [2, 2]]"), 8,
     "drivable_area.polygons_m[0]", {"expected a polygon of at least 3 vertices not all on one line", "no area"}},
    {"empty agents", with_lines({{6, "agents: []"}}, 6), 6, "agents", {"= <a list>", "expected at least one agent"}},
    {"unknown key in a path", with_lines({{11, "      other: 1"}, {12, ""}}), 11, "agents[0].path.other", {"unknown key"}},
    {"path from a start without segments", with_lines({{11, ""}, {12, ""}}), 10, "agents[0].path",
     {"missing required field segments"}},
    {"path without a base", with_line(10, "      segments0: 1"), 10, "agents[0].path.segments0", {"unknown key", "did you mean segments?"}},
    {"a segment of two kinds", with_line(12, "        - {straight_m: 10, line_to_m: [1, 1]}"), 12, "agents[0].path.segments[0]",
     {"expected one of straight_m"}},
    {"a zero-angle turn", with_line(12, "        - turn: {radius_m: 10, angle_deg: 0}"), 12,
     "agents[0].path.segments[0].turn.angle_deg", {"= 0", "a non-zero angle"}},
    {"a point that is not a pair", with_line(10, "      start: {position_m: [0, 0, 0], heading_deg: 0}"), 10,
     "agents[0].path.start.position_m", {"= <a list>", "a point [x, y] in metres"}},
    {"roundabout path without a roundabout", with_line(16, "    path: {roundabout: {entry: east, sweep_deg: 90}}"), 16,
     "agents[1].path.roundabout", {"needs the top-level roundabout"}},
    {"unknown agent in meet", with_line(19, "  - {agents: [A, C], conflict_point_m: [40, 0]}"), 19, "meet[0].agents[1]",
     {"= C", "the name of an agent"}},
    {"unknown agent in meet with a suggestion", with_line(19, "  - {agents: [A, b], conflict_point_m: [40, 0]}"), 19,
     "meet[0].agents[1]", {"= b", "(did you mean A?)"}},
    {"meet point off a path", with_line(19, "  - {agents: [A, B], conflict_point_m: [40, 3]}"), 19, "meet[0].conflict_point_m",
     {"agent A", "3 m from the path"}},
    {"meet point behind a start", with_line(19, "  - {agents: [A, B], distances_m: [-1, 3]}"), 19, "meet[0].distances_m[0]",
     {"= -1", "a number ≥ 0 [m]"}},
    {"meet without a point", with_line(19, "  - {agents: [A, B]}"), 19, "meet[0]", {"missing required field conflict_point_m"}},
    {"meet of one agent with itself", with_line(19, "  - {agents: [A, A], conflict_point_m: [40, 0]}"), 19,
     "meet[0].agents[1]", {"two different agents"}},
    {"meet of an agent that stands still", with_line(17, "    speed_kmh: 0"), 19, "meet[0]",
     {"agent B", "an agent must move to reach the conflict point"}},
    {"semantic check of the simulator, located at the agent", with_line(13, "    desired_speed_kmh: 30\n    initial_speed_kmh: 180"),
     7, "agents[0] \"A\"", {"initial_speed = 50", "at most ego.limits.speed_cap = 30 m/s"}},
    {"a meeting point behind an agent's start", with_line(13, "    desired_speed_kmh: 30\n    start_arc_length_m: 60"), 20,
     "meet[0].conflict_point_m", {"the conflict point lies 20 m behind the start of agent A"}},
    {"a history window that would keep tracks of millions of observations",
     with_lines({{5, "duration_s: 1\ntime_step_s: 0.000001"}, {13, "    desired_speed_kmh: 30\n    planner: {history_window_s: 1000}"}}),
     8, "agents[0] \"A\"", {"planner.history_window = 1000", "expected at most 1000 time steps of 1e-06 s (0.001 s)"}},
    {"semantic check of the planner configuration", with_line(13, "    desired_speed_kmh: 30\n    planner: {displacement_horizon_s: 4}"),
     7, "agents[0] \"A\"", {"planner.collision_window = 3", "at least planner.displacement_horizon = 4"}},
    {"a collision window too long for a planning step to hold",
     with_line(13, "    desired_speed_kmh: 30\n    planner: {collision_window_s: 1.0e9}"), 7, "agents[0] \"A\"",
     {"planner.collision_window = 1e+09", "expected at most 4.695e+04 s with planner.max_time_step = 0.05 s",
      "exceed the 5e8 pairs"}},
    {"a collision time step below the shortest the planner takes",
     with_line(13, "    desired_speed_kmh: 30\n    planner: {max_time_step_s: 1.0e-9}"), 7, "agents[0] \"A\"",
     {"planner.max_time_step = 1e-09", "expected at least 0.0001 s"}},
};

INSTANTIATE_TEST_SUITE_P(all, scenario_file_errors, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<error_case>& param) {
                           std::string name = param.param.what;
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

TEST(scenario_file_errors_misc, the_base_scenario_of_the_error_cases_is_valid) {
  EXPECT_NO_THROW(load_text(base, "case.yaml"));
}

TEST(scenario_file_errors_misc, an_unknown_override_names_the_parameters_the_scenario_has) {
  load_options options;
  options.overrides = {{"a_kmhh", 3.0}};
  try {
    load_text(base, "case.yaml", options);
    FAIL();
  } catch (const scenario_error& e) {
    EXPECT_EQ(e.field(), "--set a_kmhh");
    EXPECT_NE(std::string(e.what()).find("did you mean a_kmh?"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(the scenario's parameters: a_kmh)"), std::string::npos) << e.what();
  }
}

TEST(scenario_file_errors_misc, a_missing_file_a_directory_and_an_unknown_built_in_are_reported) {
  try {
    load_file("/nonexistent/dir/x.yaml");
    FAIL();
  } catch (const scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/x.yaml: cannot read the file: No such file or directory"),
              std::string::npos)
        << e.what();
  }
  try {
    load_file(std::filesystem::temp_directory_path());
    FAIL();
  } catch (const scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find(": is a directory; expected a scenario file"), std::string::npos) << e.what();
  }
  try {
    load("s2-roundabot");
    FAIL();
  } catch (const scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find("no such file or built-in scenario; did you mean s2-roundabout?"), std::string::npos)
        << e.what();
  }
}

TEST(scenario_file_errors_misc, text_that_is_not_utf8_is_refused_where_it_stands) {
  std::string text = base;
  const std::size_t at = text.find("name: ") + 6;
  text.insert(at, "\xff\xfe");
  try {
    load_text(text, "case.yaml");
    FAIL() << "a name that is not UTF-8 loaded";
  } catch (const scenario_error& e) {
    EXPECT_EQ(e.field(), "name");
    EXPECT_NE(std::string(e.what()).find("expected UTF-8 text"), std::string::npos) << e.what();
  }
  text = base;
  text.insert(at, "caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x9a\x97 ");  // é → and a car: UTF-8
  EXPECT_NO_THROW(load_text(text, "case.yaml"));
  for (const char* bad : {"\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x86"}) {  // overlong, surrogate, > U+10FFFF, cut
    text = base;
    text.insert(at, bad);
    EXPECT_THROW(load_text(text, "case.yaml"), scenario_error) << bad;
  }
}

TEST(scenario_file_errors_misc, yaml_nested_too_deep_is_reported_as_such) {
  const std::string deep = "format: maneuvermap-scenario/1\nname: x\nagents: " + std::string(5000, '[') + "\n";
  try {
    load_text(deep, "deep.yaml");
    FAIL();
  } catch (const scenario_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("deep.yaml:", 0), 0U) << e.what();
    EXPECT_NE(std::string(e.what()).find("levels deep, deeper than the YAML reader goes"), std::string::npos) << e.what();
  }
}

TEST(scenario_file_errors_misc, self_referencing_aliases_do_not_loop) {
  // yaml-cpp builds a node that contains itself; the schema-driven reader never recurses into it.
  EXPECT_THROW(load_text("format: maneuvermap-scenario/1\nname: x\nagents: &a [*a]\n", "alias.yaml"), scenario_error);
  EXPECT_THROW(load_text("&a {format: maneuvermap-scenario/1, name: x, agents: *a}\n", "alias.yaml"), scenario_error);
}

}  // namespace
