#include "mm/scenario_file/writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/planner_config.hpp"
#include "mm/scenario_file/builtin.hpp"
#include "mm/scenario_file/loader.hpp"
#include "property.hpp"

namespace {

using namespace mm::scenario_file;
using mm::vec2;
using mm::sim::path;
constexpr double pi = std::numbers::pi;

mm::sim::scenario read_back(const std::string& text) { return load_text(text, "written").scenario; }

TEST(scenario_file_writer, every_built_in_scenario_reads_back_bit_for_bit) {
  for (const builtin_scenario& b : builtin_scenarios()) {
    SCOPED_TRACE(std::string(b.name));
    const mm::sim::scenario s = load(b.name).scenario;
    const std::string text = scenario_text(s);
    EXPECT_TRUE(read_back(text) == s);
    EXPECT_EQ(scenario_text(read_back(text)), text);
    // The file states the scenario as run: no parameters, defaults or meetings left to resolve.
    EXPECT_EQ(text.find("parameters:"), std::string::npos);
    EXPECT_EQ(text.find("defaults:"), std::string::npos);
    EXPECT_EQ(text.find("meet:"), std::string::npos);
  }
}

TEST(scenario_file_writer, what_the_command_line_changes_is_in_the_written_file) {
  load_options options;
  options.overrides = {{"b_kmh", 30.0}};
  options.policy = parse_policy("const:0.5");
  options.seed = 12;
  const mm::sim::scenario s = load("s1-crossing", options).scenario;
  const mm::sim::scenario written = read_back(scenario_text(s));
  EXPECT_TRUE(written == s);
  EXPECT_FALSE(written == load("s1-crossing").scenario);
  EXPECT_EQ(written.seed, 12u);
  EXPECT_EQ(written.planning_vehicles.front().planner.policy.kind, mm::forecast_policy_kind::constant);

  load_options roads;
  roads.on_roads = true;
  const mm::sim::scenario on_roads = load("s2-roundabout", roads).scenario;
  ASSERT_FALSE(on_roads.drivable_area.open_edges.empty());
  EXPECT_TRUE(read_back(scenario_text(on_roads)) == on_roads);
}

TEST(scenario_file_writer, a_path_is_written_as_the_pieces_that_rebuild_it) {
  mm::sim::scenario s = load("s1-crossing").scenario;
  path& p = s.planning_vehicles.front().path;
  p = path::polyline(std::vector<vec2>{{-80.0, 0.1}, {-40.0, 0.0}, {-40.0 + 1e-9, 3.0}, {0.3, 7.7}});
  p.turn(13.7, -2.1).straight(9.9).line_to({1.0 / 3.0, 2.0 / 3.0}).curve(4.4, 1.0 / 7.0);
  const std::string text = scenario_text(s);
  EXPECT_TRUE(read_back(text).planning_vehicles.front().path == p);
  EXPECT_NE(text.find("curve: {length_m: "), std::string::npos) << text;
  EXPECT_NE(text.find("line_to_m: [0.3333333333333333, 0.6666666666666666]"), std::string::npos) << text;
  EXPECT_NE(text.find("straight_m: 9.9"), std::string::npos) << text;
}

TEST(scenario_file_writer, a_curve_segment_is_the_turn_of_the_same_length_and_curvature) {
  path by_turn(mm::pose{{1.0, 2.0}, 0.4});
  by_turn.turn(8.0, -1.25);
  path by_curve(mm::pose{{1.0, 2.0}, 0.4});
  by_curve.curve(10.0, -0.125);
  EXPECT_TRUE(by_turn == by_curve);
  EXPECT_THROW(path(mm::pose{}).curve(0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(path(mm::pose{}).curve(1.0, std::nan("")), std::invalid_argument);
}

TEST(scenario_file_writer, a_scenario_that_no_file_can_state_is_refused_with_the_field) {
  mm::sim::scenario s = load("s1-crossing").scenario;
  s.planning_vehicles.front().desired_speed = -1.0;
  try {
    (void)scenario_text(s);
    ADD_FAILURE() << "an invalid scenario was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("desired_speed = -1"), std::string::npos) << e.what();
  }

  s = load("s1-crossing").scenario;
  s.scripted_vehicles.front().shape.width = 0.01;  // the simulator takes it, a scenario file does not
  try {
    (void)scenario_text(s);
    ADD_FAILURE() << "a footprint below the files' smallest size was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("footprint.width_m = 0.01: expected a size from 0.05 to 1000"), std::string::npos)
        << e.what();
  }

  s = load("s1-crossing").scenario;
  s.description = "not UTF-8: \xff";
  try {
    (void)scenario_text(s);
    ADD_FAILURE() << "a description a YAML file cannot hold was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("description: a text that is not UTF-8"), std::string::npos) << e.what();
  }

  s = load("s1-crossing").scenario;
  s.planning_vehicles.front().planner.record_samples = true;
  EXPECT_THROW((void)scenario_text(s), std::invalid_argument);
}

TEST(scenario_file_writer, write_file_names_a_file_it_cannot_write) {
  const mm::sim::scenario s = load("s3-left-turn").scenario;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "mm_writer_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "s3.yaml";
  write_file(s, file);
  EXPECT_TRUE(load_file(file).scenario == s);
  try {
    write_file(s, dir / "missing" / "s3.yaml");
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const std::filesystem::filesystem_error& e) {
    EXPECT_EQ(e.path1(), dir / "missing" / "s3.yaml");
    EXPECT_EQ(e.code(), std::errc::no_such_file_or_directory);
    EXPECT_NE(std::string(e.what()).find("cannot write the scenario file"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(scenario_file_writer, the_loader_reads_open_edges_map_column_and_a_desired_speed_profile) {
  const std::string text = R"(format: maneuvermap-scenario/1
name: additions
agents:
  - name: A
    kind: planning_vehicle
    path: {start: {position_m: [0, 0], heading_deg: 0}, segments: [{curve: {length_m: 20, curvature_per_m: 0.05}}]}
    desired_speed_kmh: 36
    desired_speed_profile: [{time_s: 0, speed_mps: 10}, {time_s: 2, speed_kmh: 18}]
    planner: {map_column: false}
drivable_area:
  polygons_m: [[[-5, -5], [30, -5], [30, 30], [-5, 30]], [[30, -5], [40, -5], [40, 5]]]
  open_edges: [[0, 1], [1, 2]]
)";
  const mm::sim::scenario s = read_back(text);
  const mm::sim::planning_vehicle& a = s.planning_vehicles.front();
  EXPECT_DOUBLE_EQ(a.path.length(), 20.0);
  EXPECT_DOUBLE_EQ(a.path.end_pose().heading, 1.0);
  EXPECT_FALSE(a.planner.map_column);
  ASSERT_TRUE(a.desired_speed_profile.has_value());
  EXPECT_EQ(a.desired_speed_profile->knots.size(), 2u);
  EXPECT_DOUBLE_EQ(a.desired_speed_profile->knots[1].speed, 5.0);
  const std::vector<mm::polygon_edge> edges{{0, 1}, {1, 2}};
  EXPECT_EQ(s.drivable_area.open_edges, edges);
  EXPECT_TRUE(read_back(scenario_text(s)) == s);

  const auto error_of = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    changed.replace(changed.find(from), from.size(), to);
    try {
      (void)read_back(changed);
    } catch (const scenario_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("[1, 2]]", "[2, 0]]").find("drivable_area.open_edges[1][0] = 2: expected an integer from 0 to 1"),
            std::string::npos)
      << error_of("[1, 2]]", "[2, 0]]");
  EXPECT_NE(error_of("[1, 2]]", "[1, 3]]").find("drivable_area.open_edges[1][1] = 3: expected an integer from 0 to 2"),
            std::string::npos)
      << error_of("[1, 2]]", "[1, 3]]");
  EXPECT_NE(error_of("[1, 2]]", "[0, 1]]").find("an edge not listed before"), std::string::npos);
  EXPECT_NE(error_of("curvature_per_m: 0.05", "curvature_per_mm: 0.05").find("did you mean curvature_per_m?"),
            std::string::npos)
      << error_of("curvature_per_m: 0.05", "curvature_per_mm: 0.05");
  EXPECT_NE(error_of("length_m: 20,", "length_m: 0,").find("length_m = 0: expected"), std::string::npos)
      << error_of("length_m: 20,", "length_m: 0,");
}

// --- random scenarios ----------------------------------------------------------------------------

class random_scenario {
 public:
  explicit random_scenario(std::uint64_t seed) : rng_(seed) {}

  mm::sim::scenario make() {
    mm::sim::scenario s;
    s.name = name();
    s.description = pick(0.5) ? "" : "a line: with \"quotes\", # and\nnew lines";
    s.time_step = uniform(0.004, 0.05);
    s.duration = uniform(s.time_step, 30.0);
    s.seed = rng_();
    if (pick(0.5)) s.noise = {uniform(0.0, 0.3), uniform(0.0, 0.05), uniform(0.0, 2.0)};
    const int planning = count(1, 3);
    for (int i = 0; i < planning; ++i) s.planning_vehicles.push_back(planning_vehicle(s.time_step));
    for (int i = count(0, 3); i > 0; --i) {
      mm::sim::scripted_vehicle v;
      v.name = name();
      v.motion = motion();
      v.shape = {uniform(0.5, 12.0), uniform(0.5, 3.0)};
      if (pick(0.5)) {
        mm::sim::scripted_car_following k;
        k.following = car_following();
        k.max_acceleration = uniform(0.5, 4.0);
        k.comfortable_deceleration = uniform(0.5, 4.0);
        k.max_deceleration = uniform(4.0, 9.0);
        k.speed_gain = uniform(0.1, 3.0);
        k.follows_scripted = pick(0.5);
        v.car_following = k;
      }
      s.scripted_vehicles.push_back(v);
    }
    for (int i = count(0, 3); i > 0; --i) s.pedestrians.push_back({name(), motion(), uniform(0.1, 0.8)});
    for (int i = count(0, 2); i > 0; --i) {
      const int n = count(3, 8);
      const vec2 c{uniform(-50.0, 50.0), uniform(-50.0, 50.0)};
      const double r = uniform(0.2, 3.0);
      const double turn = uniform(-pi, pi);
      mm::sim::static_obstacle o{name(), {}};
      for (int k = 0; k < n; ++k) {
        const double angle = turn + 2.0 * pi * k / n;
        o.vertices.push_back(c + r * vec2{std::cos(angle), std::sin(angle)});
      }
      if (pick(0.5)) std::reverse(o.vertices.begin(), o.vertices.end());
      s.static_obstacles.push_back(o);
    }
    if (pick(0.5)) {
      for (int i = count(1, 4); i > 0; --i) {
        const vec2 c{uniform(-100.0, 100.0), uniform(-100.0, 100.0)};
        std::vector<vec2> polygon{c, c + vec2{uniform(5.0, 60.0), uniform(-1.0, 1.0)}, c + vec2{uniform(5.0, 60.0), uniform(5.0, 60.0)},
                                  c + vec2{uniform(-1.0, 1.0), uniform(5.0, 60.0)}};
        s.drivable_area.polygons.push_back(polygon);
        if (pick(0.5)) s.drivable_area.open_edges.push_back({s.drivable_area.polygons.size() - 1, static_cast<std::size_t>(count(0, 3))});
      }
    }
    return s;
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int count(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool pick(double p) { return std::bernoulli_distribution(p)(rng_); }

  std::string name() {
    static const std::vector<std::string> odd{"A", "car 7", "x: y", "#1", "'q'", "é → ü", "$p", "-", "true", "null", "[a]", "{b}", "  padded  ", "~",
                                              "two\nlines", "tab\there", "bell\x07", "\"quoted\"", "back\\slash"};
    return odd[static_cast<std::size_t>(count(0, static_cast<int>(odd.size()) - 1))] + "_" + std::to_string(next_name_++);
  }

  path random_path() {
    path p;
    switch (count(0, 2)) {
      case 0: {
        std::vector<vec2> points{{uniform(-100.0, 100.0), uniform(-100.0, 100.0)}};
        for (int i = count(1, 5); i > 0; --i) points.push_back(points.back() + vec2{uniform(-30.0, 30.0), uniform(-30.0, 30.0)});
        p = path::polyline(points);
        break;
      }
      case 1:
        p = path::circular_arc({uniform(-50.0, 50.0), uniform(-50.0, 50.0)}, uniform(3.0, 60.0), uniform(-10.0, 10.0),
                               pick(0.5) ? uniform(0.1, 7.0) : -uniform(0.1, 7.0));
        break;
      default: p = path(mm::pose{{uniform(-100.0, 100.0), uniform(-100.0, 100.0)}, uniform(-10.0, 10.0)}); break;
    }
    for (int i = p.empty() ? count(1, 5) : count(0, 4); i > 0; --i) {
      switch (count(0, 3)) {
        case 0: p.straight(uniform(0.5, 50.0)); break;
        case 1: p.turn(uniform(3.0, 60.0), pick(0.5) ? uniform(0.05, 4.0) : -uniform(0.05, 4.0)); break;
        case 2: p.line_to(p.end_pose().position + vec2{uniform(-30.0, 30.0), uniform(-30.0, 30.0)}); break;
        default: p.curve(uniform(0.5, 40.0), pick(0.2) ? 0.0 : uniform(-0.3, 0.3)); break;
      }
    }
    return p;
  }

  mm::sim::speed_profile profile() {
    if (pick(0.4)) return mm::sim::speed_profile::constant(uniform(0.0, 40.0));
    mm::sim::speed_profile profile;
    double t = pick(0.5) ? 0.0 : uniform(0.0, 2.0);
    for (int i = count(1, 6); i > 0; --i) {
      profile.knots.push_back({t, uniform(0.0, 40.0)});
      t += uniform(0.01, 5.0);
    }
    return profile;
  }

  mm::sim::before_start_behaviour before_start() {
    return pick(0.5) ? mm::sim::before_start_behaviour::absent : mm::sim::before_start_behaviour::wait;
  }

  mm::sim::scripted_motion motion() {
    mm::sim::scripted_motion m;
    m.path = random_path();
    m.start_time = pick(0.3) ? 0.0 : uniform(0.0, 5.0);
    m.start_arc_length = uniform(0.0, 0.5 * m.path.length());
    m.before_start = before_start();
    m.speed = profile();
    if (pick(0.4)) {
      mm::sim::stop_rule stop;
      stop.arc_length = uniform(m.start_arc_length, m.path.length());
      if (pick(0.5)) stop.duration = uniform(0.1, 10.0);
      m.stop = stop;
    }
    return m;
  }

  mm::sim::car_following_config car_following() {
    return {uniform(0.0, 3.0), uniform(0.0, 5.0), uniform(0.5, 3.0), uniform(0.0, pi)};
  }

  mm::sim::planning_vehicle planning_vehicle(double time_step) {
    mm::sim::planning_vehicle v;
    v.name = name();
    v.path = random_path();
    v.start_arc_length = uniform(0.0, 0.5 * v.path.length());
    v.start_lateral_offset = uniform(-1.0, 1.0);
    v.start_time = pick(0.3) ? 0.0 : uniform(0.0, 5.0);
    v.before_start = before_start();
    v.limits.max_acceleration = uniform(1.0, 5.0);
    v.limits.max_deceleration = uniform(3.0, 9.0);
    v.limits.max_lateral_acceleration = uniform(2.0, 8.0);
    v.limits.min_turning_radius = uniform(3.0, 8.0);
    v.limits.speed_cap = uniform(30.0, 60.0);
    v.limits.steering = pick(0.8);
    v.initial_speed = uniform(0.0, 30.0);
    v.desired_speed = uniform(0.0, 30.0);
    if (pick(0.3)) v.desired_speed_profile = profile();
    v.shape = {uniform(2.0, 6.0), uniform(1.0, 2.5)};
    mm::planner_config& c = v.planner;
    c.forecast_step = uniform(0.05, 0.25);
    c.forecast_count = static_cast<std::size_t>(count(1, 20));
    c.displacement_horizon = uniform(0.5, 1.5);
    c.collision_window = std::max(c.displacement_horizon, c.forecast_step * static_cast<double>(c.forecast_count - 1)) +
                         uniform(0.0, 2.0);
    const int policy = count(0, 2);
    c.policy.kind = policy == 0   ? mm::forecast_policy_kind::adjustable
                    : policy == 1 ? mm::forecast_policy_kind::constant
                                  : mm::forecast_policy_kind::robust;
    c.policy.constant_forecast_time = mm::forecast_times(c)[static_cast<std::size_t>(count(0, static_cast<int>(c.forecast_count) - 1))];
    c.safety_margin = pick(0.5) ? 0.0 : uniform(0.0, 1.0);
    c.urgent_steering = pick(0.5);
    c.history_window = uniform(std::max(0.2, time_step), 1.0);
    c.resolution = {static_cast<std::size_t>(count(2, 20)), static_cast<std::size_t>(count(1, 25))};
    c.max_time_step = uniform(0.01, 0.1);
    c.effort = {uniform(0.0, 2.0), uniform(0.0, 2.0)};
    c.assignment_search = pick(0.5) ? mm::assignment_search_kind::exhaustive : mm::assignment_search_kind::coordinate_ascent;
    c.max_exhaustive_assignments = static_cast<std::size_t>(count(1, 1'000'000));
    c.map_column = pick(0.7);
    v.follower.lookahead_time = uniform(0.2, 2.0);
    v.follower.min_lookahead = uniform(1.0, 10.0);
    v.follower.speed_gain = uniform(0.2, 3.0);
    v.follower.comfortable_deceleration = uniform(0.5, 4.0);
    if (pick(0.5)) v.follower.curve_lateral_acceleration = uniform(0.5, 5.0);
    if (pick(0.5)) v.follower.car_following = car_following();
    v.avoidance = pick(0.8);
    v.planning_period = static_cast<std::size_t>(count(1, 5));
    return v;
  }

  std::mt19937_64 rng_;
  int next_name_ = 0;
};

TEST(scenario_file_writer, random_scenarios_with_every_field_set_read_back_bit_for_bit) {
  const std::uint64_t seed = mm::testing::property_seed();
  const std::size_t cases = mm::testing::property_count(200);
  std::mt19937_64 seeds(seed);
  for (std::size_t i = 0; i < cases; ++i) {
    const std::uint64_t case_seed = seeds();
    const mm::sim::scenario s = random_scenario(case_seed).make();
    ASSERT_EQ(mm::sim::validation_error(s), std::nullopt) << "case seed " << case_seed << " (--seed=" << seed << ")";
    std::string text;
    try {
      text = scenario_text(s);
    } catch (const std::exception& e) {
      FAIL() << "case seed " << case_seed << " (--seed=" << seed << "): " << e.what();
    }
    const mm::sim::scenario back = read_back(text);
    ASSERT_TRUE(back == s) << "case seed " << case_seed << " (--seed=" << seed << "):\n" << text;
    ASSERT_EQ(scenario_text(back), text) << "case seed " << case_seed;
  }
}

}  // namespace
