#include "mm/scenario_file/loader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "mm/drivable_area.hpp"
#include "mm/scenario_file/builtin.hpp"

namespace {

using namespace mm::scenario_file;
constexpr double pi = std::numbers::pi;

/// Every field of the format once, with its unit alternatives and layered defaults.
const std::string full = R"(format: maneuvermap-scenario/1
name: full
description: every field once
parameters:
  a_kmh: 36
  gap_m: 2.5
  on: 1
duration_s: 4
time_step_s: 0.02
seed: 7
sensing_noise: {position_sd_m: 0.05, heading_sd_deg: 0.5, speed_sd_kmh: 0.36}
roundabout:
  center_m: [100, 0]
  radius_m: 20
  connection_radius_m: 10
  arms:
    east: {angle_deg: 0, lane_offset_m: 1.75, straight_length_m: 30}
    north: {angle_rad: 1.5707963267948966}
roads:
  - {name: main, centre_line_m: [[0, 0], [50, 0]], width_m: 7}
defaults:
  planning_vehicle:
    footprint: {length_m: 4.0, width_m: 2.0}
    planner: {safety_margin_m: 0.2, policy: const, forecast_time_s: 0.5}
  pedestrian:
    radius_m: 0.3
agents:
  - name: A
    kind: planning_vehicle
    path:
      start: {position_m: [0, 0], heading_deg: 0}
      segments:
        - straight_m: 20
        - turn: {radius_m: 10, angle_deg: 90}
        - line_to_m: [10, 40]
    start_arc_length_m: 1
    start_lateral_offset_m: 0.5
    start_time_s: 0.5
    before_start: wait
    initial_speed_mps: 5
    desired_speed_kmh: $a_kmh
    footprint: {length_m: 5}
    limits: {max_acceleration_mps2: 2, max_deceleration_mps2: 6, max_lateral_acceleration_mps2: 4,
             min_turning_radius_m: 6, speed_cap_kmh: 72, steering: true}
    planner:
      policy: adj
      urgent_steering: true
      displacement_horizon_s: 0.75
      collision_window_s: 2.5
      forecast_step_s: 0.25
      forecast_count: 9
      history_window_s: 0.4
      resolution: {accelerations: 7, curvatures: 5}
      max_time_step_s: 0.02
      effort_weights: {longitudinal: 2, lateral: 0.5}
      assignment_search: exhaustive
      max_exhaustive_assignments: 5000
    follower: {lookahead_time_s: 1, min_lookahead_m: 4, speed_gain_per_s: 2, comfortable_deceleration_mps2: 3,
               curve_lateral_acceleration_mps2: 3,
               car_following: {time_gap_s: 1.5, jam_distance_m: 3, corridor_half_width_m: 1.5}}
    avoidance: $on
    planning_period_steps: 2
  - name: R
    kind: planning_vehicle
    path: {roundabout: {entry: east, exit: north, extra_laps: 1}}
    desired_speed_mps: 8
  - name: B
    kind: scripted_vehicle
    path: {polyline_m: [[0, 30], [0, 0], [30, 0]]}
    speed_profile:
      - {time_s: 0, speed_kmh: 36}
      - {time_s: 2, speed_mps: 5}
    stop: {arc_length_m: 20, duration_s: 1.5}
    footprint: {length_m: 4, width_m: 1.7}
    car_following: {time_gap_s: 2, jam_distance_m: 1, corridor_half_width_m: 1.2, max_heading_difference_deg: 30,
                    max_acceleration_mps2: 1.5, comfortable_deceleration_mps2: 2.5, max_deceleration_mps2: 6,
                    speed_gain_per_s: 0.5, follows_scripted: false}
  - name: P
    kind: pedestrian
    path: {arc: {center_m: [0, 0], radius_m: 5, start_angle_deg: 0, sweep_deg: 180}}
    speed_mps: 1.2
  - name: Q
    kind: pedestrian
    path: {roundabout: {start_angle_deg: 90, sweep_deg: 30}}
    speed_kmh: 3.6
    radius_m: 0.4
  - name: box
    kind: static_obstacle
    vertices_m: [[5, 5], [7, 5], [7, 7], [5, 7]]
)";

TEST(scenario_file, every_field_is_mapped_onto_the_simulator_in_si_units) {
  const loaded_scenario l = load_text(full, "full.yaml");
  const mm::sim::scenario& s = l.scenario;
  EXPECT_EQ(l.source, "full.yaml");
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.description, "every field once");
  EXPECT_DOUBLE_EQ(s.duration, 4.0);
  EXPECT_DOUBLE_EQ(s.time_step, 0.02);
  EXPECT_EQ(s.seed, 7U);
  EXPECT_DOUBLE_EQ(s.noise.position_sd, 0.05);
  EXPECT_NEAR(s.noise.heading_sd, 0.5 * pi / 180.0, 1e-15);
  EXPECT_NEAR(s.noise.speed_sd, 0.1, 1e-15);
  ASSERT_EQ(s.planning_vehicles.size(), 2U);
  ASSERT_EQ(s.scripted_vehicles.size(), 1U);
  ASSERT_EQ(s.pedestrians.size(), 2U);
  ASSERT_EQ(s.static_obstacles.size(), 1U);

  const mm::sim::planning_vehicle& a = s.planning_vehicles[0];
  EXPECT_EQ(a.name, "A");
  ASSERT_EQ(a.path.segments().size(), 3U);
  EXPECT_NEAR(a.path.length(), 20.0 + 10.0 * pi / 2.0 + std::hypot(10.0 - 30.0, 40.0 - 10.0), 1e-9);
  EXPECT_DOUBLE_EQ(a.start_arc_length, 1.0);
  EXPECT_DOUBLE_EQ(a.start_lateral_offset, 0.5);
  EXPECT_DOUBLE_EQ(a.start_time, 0.5);
  EXPECT_EQ(a.before_start, mm::sim::before_start_behaviour::wait);
  EXPECT_DOUBLE_EQ(a.initial_speed, 5.0);
  EXPECT_DOUBLE_EQ(a.desired_speed, 10.0);  // $a_kmh = 36 km/h
  EXPECT_DOUBLE_EQ(a.shape.length, 5.0);    // its own value ...
  EXPECT_DOUBLE_EQ(a.shape.width, 2.0);     // ... over the defaults' width
  EXPECT_DOUBLE_EQ(a.limits.max_acceleration, 2.0);
  EXPECT_DOUBLE_EQ(a.limits.max_deceleration, 6.0);
  EXPECT_DOUBLE_EQ(a.limits.max_lateral_acceleration, 4.0);
  EXPECT_DOUBLE_EQ(a.limits.min_turning_radius, 6.0);
  EXPECT_DOUBLE_EQ(a.limits.speed_cap, 20.0);
  EXPECT_TRUE(a.limits.steering);
  EXPECT_EQ(a.planner.policy.kind, mm::forecast_policy_kind::adjustable);
  EXPECT_DOUBLE_EQ(a.planner.safety_margin, 0.2);  // from the defaults
  EXPECT_TRUE(a.planner.urgent_steering);
  EXPECT_DOUBLE_EQ(a.planner.displacement_horizon, 0.75);
  EXPECT_DOUBLE_EQ(a.planner.collision_window, 2.5);
  EXPECT_DOUBLE_EQ(a.planner.forecast_step, 0.25);
  EXPECT_EQ(a.planner.forecast_count, 9U);
  EXPECT_DOUBLE_EQ(a.planner.history_window, 0.4);
  EXPECT_EQ(a.planner.resolution.accelerations, 7U);
  EXPECT_EQ(a.planner.resolution.curvatures, 5U);
  EXPECT_DOUBLE_EQ(a.planner.max_time_step, 0.02);
  EXPECT_DOUBLE_EQ(a.planner.effort.longitudinal, 2.0);
  EXPECT_DOUBLE_EQ(a.planner.effort.lateral, 0.5);
  EXPECT_EQ(a.planner.assignment_search, mm::assignment_search_kind::exhaustive);
  EXPECT_EQ(a.planner.max_exhaustive_assignments, 5000U);
  EXPECT_DOUBLE_EQ(a.follower.lookahead_time, 1.0);
  EXPECT_DOUBLE_EQ(a.follower.min_lookahead, 4.0);
  EXPECT_DOUBLE_EQ(a.follower.speed_gain, 2.0);
  EXPECT_DOUBLE_EQ(a.follower.comfortable_deceleration, 3.0);
  EXPECT_DOUBLE_EQ(a.follower.curve_lateral_acceleration.value(), 3.0);
  ASSERT_TRUE(a.follower.car_following.has_value());
  EXPECT_DOUBLE_EQ(a.follower.car_following->time_gap, 1.5);
  EXPECT_DOUBLE_EQ(a.follower.car_following->jam_distance, 3.0);
  EXPECT_DOUBLE_EQ(a.follower.car_following->corridor_half_width, 1.5);
  EXPECT_TRUE(a.avoidance);
  EXPECT_EQ(a.planning_period, 2U);

  const mm::sim::planning_vehicle& r = s.planning_vehicles[1];
  EXPECT_DOUBLE_EQ(r.initial_speed, 8.0);  // defaults to the desired speed
  EXPECT_EQ(r.planner.policy.kind, mm::forecast_policy_kind::constant);  // from the defaults
  EXPECT_DOUBLE_EQ(r.planner.policy.constant_forecast_time, 0.5);
  const mm::sim::roundabout ring{{100.0, 0.0}, 20.0, 10.0};
  const mm::sim::roundabout_arm east{0.0, 1.75, 30.0};
  const mm::sim::roundabout_arm north{pi / 2.0, 0.0, 50.0};
  EXPECT_NEAR(r.path.length(), mm::sim::roundabout_route(ring, east, north, 1).length(), 1e-9);

  const mm::sim::scripted_vehicle& b = s.scripted_vehicles[0];
  EXPECT_EQ(b.motion.path.segments().size(), 2U);
  ASSERT_EQ(b.motion.speed.knots.size(), 2U);
  EXPECT_DOUBLE_EQ(b.motion.speed.knots[0].speed, 10.0);
  EXPECT_DOUBLE_EQ(b.motion.speed.knots[1].time, 2.0);
  EXPECT_DOUBLE_EQ(b.motion.speed.knots[1].speed, 5.0);
  ASSERT_TRUE(b.motion.stop.has_value());
  EXPECT_DOUBLE_EQ(b.motion.stop->arc_length, 20.0);
  EXPECT_DOUBLE_EQ(b.motion.stop->duration.value(), 1.5);
  EXPECT_DOUBLE_EQ(b.shape.width, 1.7);
  ASSERT_TRUE(b.car_following.has_value());
  EXPECT_DOUBLE_EQ(b.car_following->following.time_gap, 2.0);
  EXPECT_DOUBLE_EQ(b.car_following->following.jam_distance, 1.0);
  EXPECT_DOUBLE_EQ(b.car_following->following.corridor_half_width, 1.2);
  EXPECT_NEAR(b.car_following->following.max_heading_difference, pi / 6.0, 1e-15);
  EXPECT_DOUBLE_EQ(b.car_following->max_acceleration, 1.5);
  EXPECT_DOUBLE_EQ(b.car_following->comfortable_deceleration, 2.5);
  EXPECT_DOUBLE_EQ(b.car_following->max_deceleration, 6.0);
  EXPECT_DOUBLE_EQ(b.car_following->speed_gain, 0.5);
  EXPECT_FALSE(b.car_following->follows_scripted);

  EXPECT_NEAR(s.pedestrians[0].motion.path.length(), 5.0 * pi, 1e-9);
  EXPECT_DOUBLE_EQ(s.pedestrians[0].radius, 0.3);  // from the defaults
  EXPECT_DOUBLE_EQ(s.pedestrians[0].motion.speed.knots[0].speed, 1.2);
  EXPECT_DOUBLE_EQ(s.pedestrians[1].radius, 0.4);
  EXPECT_DOUBLE_EQ(s.pedestrians[1].motion.speed.knots[0].speed, 1.0);
  EXPECT_NEAR(s.pedestrians[1].motion.path.length(), 20.0 * pi / 6.0, 1e-9);
  EXPECT_EQ(s.static_obstacles[0].vertices.size(), 4U);

  ASSERT_TRUE(l.roundabout.has_value());
  ASSERT_EQ(l.roundabout->arms.size(), 2U);
  EXPECT_EQ(l.roundabout->arms[1].name, "north");
  EXPECT_DOUBLE_EQ(l.roundabout->arms[1].arm.straight_length, 50.0);  // default
  ASSERT_EQ(l.roads.size(), 1U);
  EXPECT_DOUBLE_EQ(l.roads[0].width, 7.0);
  ASSERT_EQ(l.parameters.size(), 3U);
  EXPECT_EQ(l.parameters[1].name, "gap_m");
}

TEST(scenario_file, the_drivable_area_is_the_roads_with_their_bends_closed_and_the_polygons_given) {
  const std::string text = R"(format: maneuvermap-scenario/1
name: on-the-road
roads:
  - {centre_line_m: [[0, 0], [50, 0], [50, 50]], width_m: 4}
drivable_area:
  roads: true
  polygons_m:
    - [[-10, -10], [0, -10], [0, 10]]
agents:
  - {name: A, kind: planning_vehicle, desired_speed_kmh: 30,
     path: {start: {position_m: [1, 0], heading_deg: 0}, segments: [{straight_m: 40}]}}
)";
  const loaded_scenario l = load_text(text, "road.yaml");
  const std::vector<std::vector<mm::vec2>>& area = l.scenario.drivable_area.polygons;
  // A 4 m wide rectangle, the triangle that closes the outside of the left bend at (50, 0), the
  // second rectangle, the polygon given; the road's two ends lead on (open edges).
  ASSERT_EQ(area.size(), 4U);
  EXPECT_EQ(area[0], (std::vector<mm::vec2>{{0, -2}, {50, -2}, {50, 2}, {0, 2}}));
  EXPECT_EQ(area[1], (std::vector<mm::vec2>{{50, 0}, {50, -2}, {52, 0}}));
  EXPECT_EQ(area[2], (std::vector<mm::vec2>{{52, 0}, {52, 50}, {48, 50}, {48, 0}}));
  EXPECT_EQ(area[3], (std::vector<mm::vec2>{{-10, -10}, {0, -10}, {0, 10}}));
  EXPECT_EQ(l.scenario.drivable_area.open_edges, (std::vector<mm::polygon_edge>{{0, 3}, {2, 1}}));
  // Their union is the road: its outer corner at the bend is bevelled, the inside is whole.
  const mm::drivable_area road(l.scenario.drivable_area);
  EXPECT_TRUE(road.contains({51.9, -0.05}));
  EXPECT_TRUE(road.contains({50.9, -0.9}));
  EXPECT_FALSE(road.contains({51.9, -1.9}));
  EXPECT_TRUE(road.contains({49.0, 1.0}));
  // The ends are no boundary: nothing of it lies across the road at x = 0 (where the given triangle
  // bounds it only below y = −2... its edge x = 0 runs from −10 to 10) or at y = 50.
  for (const mm::segment& e : road.boundary()) {
    EXPECT_FALSE(e.a.y == 50.0 && e.b.y == 50.0) << "the road's far end is open";
  }
  // Without drivable_area: none.
  EXPECT_TRUE(load_text(full, "full.yaml").scenario.drivable_area.empty());
}

TEST(scenario_file, the_drivable_area_of_a_roundabout_is_its_lanes) {
  const std::string head = R"(format: maneuvermap-scenario/1
name: in-the-ring
roundabout:
  radius_m: 25
  connection_radius_m: 12.66
  arms:
    east: {angle_deg: 0, lane_offset_m: 1.75, straight_length_m: 60}
    north: {angle_deg: 90, lane_offset_m: 1.75, straight_length_m: 60}
agents:
  - {name: A, kind: planning_vehicle, desired_speed_kmh: 30, path: {roundabout: {entry: east, exit: north}}}
)";
  const loaded_scenario l = load_text(head + "drivable_area: {roundabout: true}\n", "ring.yaml");
  std::vector<mm::sim::roundabout_arm> arms;
  for (const named_arm& a : l.roundabout->arms) arms.push_back(a.arm);
  const mm::drivable_outline lanes = mm::sim::roundabout_lanes(l.roundabout->ring, arms, 3.5);  // true: 3.5 m lanes
  EXPECT_EQ(l.scenario.drivable_area.polygons, lanes.polygons);
  EXPECT_EQ(l.scenario.drivable_area.open_edges, lanes.open_edges);
  const mm::drivable_area area(l.scenario.drivable_area);
  EXPECT_TRUE(area.contains({-25.0, 0.0}));   // the ring, opposite the arms
  EXPECT_FALSE(area.contains({-27.0, 0.0}));  // 2 m outside its centre line
  EXPECT_TRUE(area.contains({60.0, 3.0}));    // the east arm's entry lane
  EXPECT_FALSE(area.contains({-60.0, 1.75})); // no west arm
  // A width of its own, and a polygon besides.
  const loaded_scenario wide = load_text(head + "drivable_area:\n  roundabout: {lane_width_m: 4.5}\n  polygons_m: [[[-1, -1], [1, -1], [0, 1]]]\n", "ring.yaml");
  const mm::drivable_area wider(wide.scenario.drivable_area);
  EXPECT_TRUE(wider.contains({-27.0, 0.0}));
  EXPECT_TRUE(wider.contains({0.0, 0.0}));
  EXPECT_EQ(wide.scenario.drivable_area.polygons.size(), mm::sim::roundabout_lanes(l.roundabout->ring, arms, 4.5).polygons.size() + 1);
  // false: no lanes.
  EXPECT_TRUE(load_text(head + "drivable_area: {roundabout: false, polygons_m: [[[-1, -1], [1, -1], [0, 1]]]}\n", "ring.yaml")
                  .scenario.drivable_area.polygons.size() == 1);
}

TEST(scenario_file, on_roads_makes_the_drivable_area_of_the_roads_and_the_roundabout_s_lanes) {
  load_options on_roads;
  on_roads.on_roads = true;
  // S1's roads: as drivable_area: {roads: true}; S2's roundabout: as {roundabout: true}.
  const loaded_scenario s1 = load("s1-crossing", on_roads);
  const loaded_scenario s1_plain = load("s1-crossing");
  EXPECT_TRUE(s1_plain.scenario.drivable_area.empty());
  ASSERT_FALSE(s1.roads.empty());
  mm::drivable_outline roads;
  for (const road& r : s1.roads) {
    const mm::drivable_outline piece = road_polygons(r);
    for (const mm::polygon_edge& e : piece.open_edges) roads.open_edges.push_back({roads.polygons.size() + e.polygon, e.edge});
    roads.polygons.insert(roads.polygons.end(), piece.polygons.begin(), piece.polygons.end());
  }
  EXPECT_EQ(s1.scenario.drivable_area.polygons, roads.polygons);
  EXPECT_EQ(s1.scenario.drivable_area.open_edges, roads.open_edges);
  const loaded_scenario s2 = load("s2-roundabout", on_roads);
  std::vector<mm::sim::roundabout_arm> arms;
  for (const named_arm& a : s2.roundabout->arms) arms.push_back(a.arm);
  EXPECT_EQ(s2.scenario.drivable_area.polygons, mm::sim::roundabout_lanes(s2.roundabout->ring, arms, 3.5).polygons);
  // Nothing to drive on, or a drivable area of its own: refused, naming the option.
  const std::string bare = R"(format: maneuvermap-scenario/1
name: bare
agents:
  - {name: A, kind: planning_vehicle, desired_speed_kmh: 30,
     path: {start: {position_m: [0, 0], heading_deg: 0}, segments: [{straight_m: 50}]}}
)";
  try {
    load_text(bare, "bare.yaml", on_roads);
    FAIL() << "--on-roads without roads was accepted";
  } catch (const scenario_error& e) {
    EXPECT_EQ(e.field(), "--on-roads");
    EXPECT_NE(std::string(e.what()).find("no roads: and no roundabout:"), std::string::npos) << e.what();
  }
  const std::string own = bare + "roads: [{centre_line_m: [[0, 0], [50, 0]]}]\ndrivable_area: {roads: true}\n";
  EXPECT_NO_THROW(load_text(own, "own.yaml"));
  EXPECT_THROW(load_text(own, "own.yaml", on_roads), scenario_error);
}

TEST(scenario_file, parameters_take_their_defaults_and_command_line_overrides_replace_them) {
  load_options options;
  options.overrides = {{"a_kmh", 72.0}, {"on", 0.0}, {"a_kmh", 54.0}};  // the later one wins
  const loaded_scenario l = load_text(full, "full.yaml", options);
  EXPECT_DOUBLE_EQ(l.scenario.planning_vehicles[0].desired_speed, 15.0);
  EXPECT_FALSE(l.scenario.planning_vehicles[0].avoidance);
  EXPECT_DOUBLE_EQ(l.parameters[0].value, 54.0);
  EXPECT_DOUBLE_EQ(l.parameters[0].default_value, 36.0);

  options.overrides = {{"a_kmh", -1.0}};
  EXPECT_THROW(load_text(full, "full.yaml", options), scenario_error);  // a negative desired speed
}

TEST(scenario_file, a_planning_vehicle_may_take_the_robust_policy) {
  std::string text = full;
  const std::size_t at = text.find("      policy: adj\n");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("      policy: adj").size(), "      policy: robust");
  const loaded_scenario l = load_text(text, "full.yaml");
  EXPECT_EQ(l.scenario.planning_vehicles[0].planner.policy.kind, mm::forecast_policy_kind::robust);
  load_options options;
  options.policy = parse_policy("robust");
  for (const mm::sim::planning_vehicle& v : load_text(full, "full.yaml", options).scenario.planning_vehicles) {
    EXPECT_EQ(v.planner.policy.kind, mm::forecast_policy_kind::robust);
  }
}

TEST(scenario_file, the_command_line_replaces_the_policy_of_every_planning_vehicle_and_the_seed) {
  load_options options;
  options.policy = parse_policy("const:1.5");
  options.seed = 42;
  const loaded_scenario l = load_text(full, "full.yaml", options);
  for (const mm::sim::planning_vehicle& v : l.scenario.planning_vehicles) {
    EXPECT_EQ(v.planner.policy.kind, mm::forecast_policy_kind::constant);
    EXPECT_DOUBLE_EQ(v.planner.policy.constant_forecast_time, 1.5);
  }
  EXPECT_EQ(l.scenario.seed, 42U);
  options.policy = parse_policy("const:1.3");  // off the 0.25 s grid of A
  try {
    load_text(full, "full.yaml", options);
    FAIL() << "expected a scenario_error";
  } catch (const scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find("constant_forecast_time = 1.3"), std::string::npos) << e.what();
  }
}

TEST(scenario_file, policies_and_overrides_parse_strictly) {
  EXPECT_EQ(parse_policy("adj")->kind, mm::forecast_policy_kind::adjustable);
  EXPECT_DOUBLE_EQ(parse_policy("const:0.5")->constant_forecast_time, 0.5);
  EXPECT_FALSE(parse_policy("const:").has_value());
  EXPECT_FALSE(parse_policy("const:-1").has_value());
  EXPECT_FALSE(parse_policy("const:1s").has_value());
  EXPECT_FALSE(parse_policy("ADJ").has_value());
  EXPECT_EQ(policy_name(*parse_policy("const:1.0")), "const:1");
  EXPECT_EQ(policy_name(*parse_policy("adj")), "adj");
  EXPECT_EQ(parse_policy("robust")->kind, mm::forecast_policy_kind::robust);
  EXPECT_EQ(policy_name(*parse_policy("robust")), "robust");
  EXPECT_FALSE(parse_policy("robust:1").has_value());
  EXPECT_EQ(parse_override("a_kmh=40")->second, 40.0);
  EXPECT_EQ(parse_override("a_kmh=40")->first, "a_kmh");
  EXPECT_FALSE(parse_override("a_kmh").has_value());
  EXPECT_FALSE(parse_override("=4").has_value());
  EXPECT_FALSE(parse_override("a=x").has_value());
  EXPECT_FALSE(parse_override("a=nan").has_value());
}

TEST(scenario_file, a_meeting_delays_the_agent_that_would_arrive_first) {
  const std::string text = R"(format: maneuvermap-scenario/1
name: meet
agents:
  - name: A
    kind: planning_vehicle
    path: {start: {position_m: [-40, 0], heading_deg: 0}, segments: [{straight_m: 100}]}
    desired_speed_mps: 10
  - name: B
    kind: scripted_vehicle
    path: {start: {position_m: [0, 60], heading_deg: -90}, segments: [{straight_m: 100}]}
    speed_mps: 10
  - name: P
    kind: pedestrian
    path: {start: {position_m: [20, -5], heading_deg: 90}, segments: [{straight_m: 10}]}
    speed_mps: 1
meet:
  - {agents: [A, B], conflict_point_m: [0, 0]}
  - {agents: [P, A], distances_m: [5, 60], lag_s: 0.5}
)";
  const loaded_scenario l = load_text(text, "meet.yaml");
  // A: 40 m (4 s) to B's road; B: 60 m (6 s): A waits 2 s. P must reach A's lane 0.5 s before
  // A reaches x = 20, i.e. at 2 + 6 − 0.5 = 7.5 s, after 5 s of walking: P starts at 2.5 s.
  EXPECT_DOUBLE_EQ(l.scenario.planning_vehicles[0].start_time, 2.0);
  EXPECT_DOUBLE_EQ(l.scenario.scripted_vehicles[0].motion.start_time, 0.0);
  EXPECT_DOUBLE_EQ(l.scenario.pedestrians[0].motion.start_time, 2.5);
  ASSERT_EQ(l.meetings.size(), 2U);
  EXPECT_DOUBLE_EQ(l.meetings[0].first_distance, 40.0);
  EXPECT_DOUBLE_EQ(l.meetings[0].second_distance, 60.0);
  EXPECT_DOUBLE_EQ(l.meetings[0].first_travel, 4.0);
  EXPECT_DOUBLE_EQ(l.meetings[0].first_start, 2.0);
  EXPECT_DOUBLE_EQ(l.meetings[1].lag, 0.5);
  EXPECT_DOUBLE_EQ(l.meetings[1].first_start, 2.5);
  EXPECT_DOUBLE_EQ(l.meetings[1].second_start, 2.0);
}

TEST(scenario_file, the_built_in_s3_meets_47_m_along_a_and_27_m_along_b_at_each_ones_speed) {
  for (double a_kmh : {25.0, 45.0}) {
    load_options options;
    options.overrides = {{"a_kmh", a_kmh}, {"b_kmh", 30.0}};
    const loaded_scenario l = load("s3-left-turn", options);
    ASSERT_EQ(l.meetings.size(), 1U);
    EXPECT_NEAR(l.meetings[0].first_distance, 47.0, 1e-3);
    EXPECT_NEAR(l.meetings[0].second_distance, 27.0, 1e-3);
    const mm::sim::planning_vehicle& a = l.scenario.planning_vehicles[0];
    const mm::sim::scripted_vehicle& b = l.scenario.scripted_vehicles[0];
    EXPECT_DOUBLE_EQ(a.initial_speed, a_kmh / 3.6);
    EXPECT_DOUBLE_EQ(a.desired_speed, a_kmh / 3.6);
    const double a_arrival = a.start_time + 47.0 / (a_kmh / 3.6);
    const double b_arrival = b.motion.start_time + 27.0 / (30.0 / 3.6);
    EXPECT_NEAR(a_arrival, b_arrival, 1e-3);
    EXPECT_EQ(std::min(a.start_time, b.motion.start_time), 0.0);  // only the earlier one waits
  }
}

TEST(scenario_file, the_built_in_s2_times_b_along_the_ring_to_a_s_merge_point) {
  const loaded_scenario l = load("s2-roundabout");
  ASSERT_TRUE(l.roundabout.has_value());
  const mm::sim::roundabout& ring = l.roundabout->ring;
  const mm::sim::roundabout_arm& east = l.roundabout->arms[0].arm;
  // The exit lane leaves 45° of arc before the entry lane joins.
  EXPECT_NEAR(mm::sim::merge_angle(ring, east) - mm::sim::diverge_angle(ring, east), pi / 4.0, 1e-3);
  const double merge = mm::sim::merge_angle(ring, east);
  EXPECT_NEAR(l.meetings[0].second_distance, 25.0 * (merge - (-60.0 * pi / 180.0)), 1e-6);
  EXPECT_NEAR(l.meetings[0].first_distance, 15.0 + 12.66 * (pi / 2.0 - merge), 1e-6);
}

TEST(scenario_file, every_built_in_scenario_loads_and_is_valid) {
  ASSERT_EQ(builtin_scenarios().size(), 9U);
  for (const builtin_scenario& b : builtin_scenarios()) {
    const loaded_scenario l = load(b.name);
    EXPECT_EQ(l.scenario.name, b.name) << "a built-in's name is its file name";
    EXPECT_FALSE(l.scenario.description.empty()) << b.name;
    EXPECT_FALSE(mm::sim::validation_error(l.scenario).has_value()) << b.name;
    // The paper's scenarios have one ego; s6 is the many-agent one (docs/performance.md).
    EXPECT_EQ(l.scenario.planning_vehicles.size(), b.name == "s6-busy-roundabout" ? 50U : 1U) << b.name;
  }
  EXPECT_EQ(find_builtin("nope"), nullptr);
  ASSERT_NE(find_builtin("s4-pedestrian"), nullptr);
}

TEST(scenario_file, a_built_in_file_on_disk_is_the_embedded_one) {
  const char* root = std::getenv("MM_SOURCE_DIR");
  ASSERT_NE(root, nullptr);
  const loaded_scenario from_disk = load(std::string(root) + "/scenarios/s5-several-obstacles.yaml");
  const loaded_scenario embedded = load("s5-several-obstacles");
  EXPECT_EQ(from_disk.scenario.name, embedded.scenario.name);
  EXPECT_EQ(from_disk.scenario.pedestrians[0].motion.start_time, embedded.scenario.pedestrians[0].motion.start_time);
  EXPECT_EQ(embedded.source, "builtin:s5-several-obstacles");
}

}  // namespace

namespace mm::scenario_file {
namespace {

TEST(scenario_file, the_s6_variant_with_car_following_is_s6_with_every_driver_keeping_its_distance) {
  const char* root = std::getenv("MM_SOURCE_DIR");
  ASSERT_NE(root, nullptr);
  const loaded_scenario following = load(std::string(root) + "/examples/scenarios/s6-busy-roundabout-following.yaml");
  const loaded_scenario s6 = load("s6-busy-roundabout");
  const auto& with = following.scenario.planning_vehicles;
  const auto& without = s6.scenario.planning_vehicles;
  ASSERT_EQ(with.size(), 50U);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    EXPECT_EQ(with[i].name, without[i].name);
    EXPECT_EQ(with[i].start_arc_length, without[i].start_arc_length) << with[i].name;
    EXPECT_EQ(with[i].path.length(), without[i].path.length()) << with[i].name;
    EXPECT_EQ(with[i].desired_speed, without[i].desired_speed) << with[i].name;
    EXPECT_FALSE(without[i].follower.car_following.has_value()) << with[i].name;
    ASSERT_TRUE(with[i].follower.car_following.has_value()) << with[i].name;
    EXPECT_EQ(with[i].follower.car_following->time_gap, 1.0);
    EXPECT_EQ(with[i].follower.car_following->jam_distance, 2.0);
  }
}

}  // namespace
}  // namespace mm::scenario_file
