#include "mm/sim/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/scenarios.hpp"

namespace {

using namespace mm::sim;
using mm::sim::testing::crossing;
using mm::sim::testing::cruising;
using mm::sim::testing::scripted;
using mm::sim::testing::straight_path;
constexpr double pi = std::numbers::pi;

TEST(simulation, a_vehicle_that_does_not_plan_hits_the_crossing_vehicle_at_the_first_overlapping_step) {
  simulation sim(crossing(false));
  run(sim);
  // A (4.5 × 1.8, east at 100/9 m/s from x = 0) and B (south along x = 40 from y = 36 at 10 m/s)
  // overlap once A's front passes B's west side, x_A + 2.25 > 39.1, and B's rear end has come
  // down to A's north side, y_B − 2.25 < 0.9: the later of 36.85/v_A = 3.3165 s and 3.285 s.
  const double overlap = std::max(36.85 / (40.0 / 3.6), 32.85 / 10.0);
  const double first_step = std::ceil(overlap / 0.01) * 0.01;
  ASSERT_EQ(sim.crashes().size(), 1U);
  EXPECT_NEAR(sim.crashes()[0].time, first_step, 1e-9);
  EXPECT_EQ(sim.crashes()[0].first, 0U);
  EXPECT_EQ(sim.crashes()[0].second, 1U);
  EXPECT_TRUE(sim.ended());
  EXPECT_NEAR(sim.time(), first_step, 1e-9);  // the only planning vehicle crashed: the run ends
  EXPECT_EQ(sim.state(0).status, agent_status::crashed);
  EXPECT_EQ(sim.state(1).status, agent_status::crashed);
  EXPECT_EQ(sim.state(0).speed, 0.0);

  const run_metrics m = sim.metrics(0);
  EXPECT_TRUE(m.crash);
  EXPECT_EQ(m.crash_with, "B");
  EXPECT_NEAR(*m.crash_time_s, first_step, 1e-9);
  EXPECT_EQ(*m.min_dist_m, 0.0);
  EXPECT_EQ(m.closest_agent, "B");
  EXPECT_FALSE(m.ttc_at_min_s.has_value());
  EXPECT_NEAR(*m.speed_kmh, 40.0, 1e-9);
  EXPECT_EQ(m.bypass, bypass_side::none);
  EXPECT_EQ(m.planning_steps, 0U);

  const std::size_t steps = sim.step_index();
  sim.step();
  EXPECT_EQ(sim.step_index(), steps);  // no-op once ended
}

TEST(simulation, a_crashed_vehicle_stops_and_stays_an_obstacle_for_the_others) {
  scenario s;
  s.duration = 5.0;
  // A drives into a wall at x = 20; C follows 12 m behind on the same road and drives into A.
  s.planning_vehicles.push_back(cruising("A", straight_path({0.0, 0.0}, 0.0, 100.0), 10.0));
  s.planning_vehicles.push_back(cruising("C", straight_path({-12.0, 0.0}, 0.0, 112.0), 10.0));
  s.planning_vehicles[0].avoidance = false;
  s.planning_vehicles[1].avoidance = false;
  s.static_obstacles.push_back({"wall", {{20.0, -3.0}, {21.0, -3.0}, {21.0, 3.0}, {20.0, 3.0}}});
  simulation sim(s);
  run(sim);
  ASSERT_EQ(sim.crashes().size(), 2U);
  // A's front (x + 2.25) passes 20 at x > 17.75: t > 1.775 s. C then hits the standing A.
  EXPECT_NEAR(sim.crashes()[0].time, 1.78, 1e-9);
  EXPECT_EQ(sim.info(sim.crashes()[0].second).name, "wall");
  const double a_rear = sim.state(0).pose.position.x - 2.25;
  // C's front reaches A's rear at (a_rear − 2.25 + 12)/10 s; touching is not overlapping, so the
  // crash is the step after.
  EXPECT_NEAR(sim.crashes()[1].time, (std::floor((a_rear - 2.25 + 12.0) / 10.0 / 0.01 + 1e-6) + 1.0) * 0.01, 1e-9);
  EXPECT_EQ(sim.crashes()[1].first, 0U);
  EXPECT_EQ(sim.crashes()[1].second, 1U);
  EXPECT_EQ(sim.metrics(1).crash_with, "A");
  EXPECT_EQ(sim.state(2).status, agent_status::active);  // static obstacles never crash
  EXPECT_TRUE(sim.ended());
  EXPECT_LT(sim.time(), 3.0);
}

TEST(simulation, metrics_of_a_hand_computed_close_pass) {
  // A stands 0.5 m right of its path (box x ∈ [−2.25, 2.25], y ∈ [−1.4, 0.4]). A pedestrian walks
  // south along x = 0 at 1.4 m/s from y = 10.004, turns back at y = 3 (reached at 5.0029 s) and
  // walks north again. Sampled every 10 ms, its lowest sample is y = 3.004 at t = 5.00 (the next
  // is y = 3.010): gap 3.004 − 0.4 − 0.35 = 2.254 m. With both velocities frozen then, it would
  // touch A's roof after 2.254 / 1.4 = 1.61 s.
  scenario s;
  s.duration = 8.0;
  planning_vehicle a = cruising("A", straight_path({-10.0, 0.0}, 0.0, 100.0), 0.0);
  a.start_arc_length = 10.0;
  a.start_lateral_offset = -0.5;
  a.avoidance = false;
  s.planning_vehicles.push_back(a);
  pedestrian p;
  p.name = "P";
  const std::vector<mm::vec2> walk{{0.0, 10.004}, {0.0, 3.0}, {0.0, 10.0}};
  p.motion.path = path::polyline(walk);
  p.motion.speed = speed_profile::constant(1.4);
  s.pedestrians.push_back(p);
  simulation sim(s);
  run(sim);
  const run_metrics m = sim.metrics(0);
  EXPECT_FALSE(m.crash);
  EXPECT_NEAR(*m.min_dist_m, 2.254, 1e-9);
  EXPECT_NEAR(*m.min_dist_time_s, 5.0, 1e-9);
  EXPECT_EQ(m.closest_agent, "P");
  ASSERT_TRUE(m.ttc_at_min_s.has_value());
  EXPECT_NEAR(*m.ttc_at_min_s, 2.254 / 1.4, 1e-5);
  EXPECT_EQ(m.bypass, bypass_side::right);
  EXPECT_NEAR(m.lateral_offset_at_min_m, -0.5, 1e-12);
  EXPECT_DOUBLE_EQ(*m.speed_kmh, 0.0);
  EXPECT_DOUBLE_EQ(m.max_speed_kmh, 0.0);
  EXPECT_EQ(m.time_in_brake_s + m.time_in_accel_s, 0.0);
}

TEST(simulation, a_planning_vehicle_avoids_the_crossing_vehicle_it_would_otherwise_hit) {
  // The same crossing as the crash test, with the planner on (ADJ, defaults) and a safety
  // margin of 0.3 m (spec §2). Without a margin the minimal-effort choice grazes B and the core's
  // 50 ms collision sampling lets a corner clip through: see docs/simulator.md.
  scenario s = crossing(true);
  s.duration = 4.5;
  s.planning_vehicles[0].planner.safety_margin = 0.3;
  simulation sim(s);
  run(sim);
  const run_metrics m = sim.metrics(0);
  EXPECT_FALSE(m.crash);
  EXPECT_TRUE(sim.crashes().empty());
  EXPECT_EQ(m.closest_agent, "B");
  EXPECT_GT(*m.min_dist_m, 0.1);
  EXPECT_LT(*m.min_dist_m, 1.5);
  // It yields: brakes (to about 28 km/h), lets B pass first and goes round its tail on the left.
  EXPECT_GT(m.time_in_brake_s, 1.0);
  EXPECT_LT(m.min_speed_kmh, 35.0);
  EXPECT_GT(m.min_speed_kmh, 15.0);
  EXPECT_EQ(m.bypass, bypass_side::left);
  EXPECT_GT(*m.min_dist_time_s, 3.6);
  EXPECT_EQ(m.planning_steps, sim.step_index());  // every step but the last, at which it ended
  EXPECT_EQ(m.cpu_median_us, 0.0);  // not measured
}

TEST(simulation, replanning_on_the_planning_input_reproduces_the_decision) {
  scenario s = crossing(true);
  simulation sim(s);
  while (sim.time() < 2.0 - 1e-9) sim.step();
  ASSERT_TRUE(sim.planned_now(0));
  const std::optional<mm::plan_input> input = sim.planning_input(0);
  ASSERT_TRUE(input.has_value());
  ASSERT_EQ(input->obstacles.size(), 1U);
  EXPECT_EQ(input->obstacles[0].id, 1U);
  EXPECT_EQ(input->obstacles[0].kind, mm::obstacle_kind::vehicle);
  EXPECT_DOUBLE_EQ(input->time, 2.0);
  const mm::plan_result again = mm::plan(*input);
  const plan_record& last = *sim.last_plan(0);
  EXPECT_DOUBLE_EQ(last.time, 2.0);
  EXPECT_EQ(again.command, last.result.command);
  EXPECT_EQ(again.mode, last.result.mode);
  EXPECT_EQ(again.mi_brake, last.result.mi_brake);
  EXPECT_EQ(again.mi_accelerate, last.result.mi_accelerate);
  EXPECT_EQ(last.result.mi_brake.size(), 17U);
  EXPECT_NE(last.result.mode, mm::planning_mode::nominal);  // B is a threat at 2 s
  EXPECT_DOUBLE_EQ(sim.state(0).acceleration, last.result.command.acceleration);
  EXPECT_DOUBLE_EQ(sim.state(0).curvature, last.result.command.curvature);
}

TEST(simulation, an_id_that_does_not_exist_is_an_out_of_range_error_that_names_the_ids_there_are) {
  const simulation sim(crossing(true));  // A plans (id 0), B does not (id 1)
  ASSERT_EQ(sim.agent_count(), 2U);
  ASSERT_EQ(sim.planning_vehicle_count(), 1U);
  const auto message = [](auto&& call) {
    try {
      call();
    } catch (const std::out_of_range& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([&] { (void)sim.state(2); }), "state: agent 2 does not exist: expected an id from 0 to 1");
  EXPECT_EQ(message([&] { (void)sim.info(7); }), "info: agent 7 does not exist: expected an id from 0 to 1");
  EXPECT_EQ(message([&] { (void)sim.last_plan(1); }),
            "last_plan: planning vehicle 1 does not exist: expected an id from 0 to 0");
  EXPECT_EQ(message([&] { (void)sim.planned_now(1); }),
            "planned_now: planning vehicle 1 does not exist: expected an id from 0 to 0");
  EXPECT_EQ(message([&] { (void)sim.planning_input(1); }),
            "planning_input: planning vehicle 1 does not exist: expected an id from 0 to 0");
  EXPECT_EQ(message([&] { (void)sim.metrics(1); }),
            "metrics: planning vehicle 1 does not exist: expected an id from 0 to 0");
  EXPECT_EQ(message([&] { (void)sim.state(1); }), "no error");
}

TEST(simulation, a_command_given_from_outside_drives_the_vehicle_until_its_next_decision) {
  // A, which plans, is braked to a stop from outside at 1 s; it senses and plans on, and its plans
  // stay its own planner's.
  scenario s = crossing(true);
  s.duration = 3.0;
  s.planning_vehicles[0].planner.safety_margin = 0.3;
  const double hardest = s.planning_vehicles[0].limits.max_deceleration;
  simulation sim(s);
  while (sim.time() < 1.0 - 1e-9) sim.step();
  const double speed_at_one = sim.state(0).speed;
  const mm::vec2 at_one = sim.state(0).pose.position;
  while (!sim.ended()) {
    sim.override_command(0, {-hardest, 0.0});
    EXPECT_EQ(sim.state(0).acceleration, -hardest);
    EXPECT_EQ(sim.state(0).curvature, 0.0);
    sim.step();
    if (sim.ended()) break;
    EXPECT_TRUE(sim.planned_now(0));
    EXPECT_EQ(sim.last_plan(0)->result.command, mm::plan(*sim.planning_input(0)).command);
  }
  // v(t) = max(0, v(1 s) − d_max (t − 1 s)): stopped after 11.1/7 = 1.6 s, before B crosses.
  EXPECT_EQ(sim.state(0).speed, 0.0);
  // Straight on (κ = 0) from where it was at 1 s, by its braking distance v²/(2 d_max).
  const mm::vec2 moved = sim.state(0).pose.position - at_one;
  EXPECT_NEAR(std::hypot(moved.x, moved.y), speed_at_one * speed_at_one / (2.0 * hardest), 1e-9);
  EXPECT_FALSE(sim.metrics(0).crash);

  // Its own command, given back from outside, leaves the run as it was, bit for bit.
  simulation own(s);
  simulation given(s);
  while (!own.ended()) {
    given.override_command(0, {own.state(0).acceleration, own.state(0).curvature});
    own.step();
    given.step();
    ASSERT_EQ(own.state(0).pose.position.x, given.state(0).pose.position.x);
    ASSERT_EQ(own.state(0).pose.position.y, given.state(0).pose.position.y);
  }
}

TEST(simulation, a_command_from_outside_holds_until_the_next_planning_step_of_a_vehicle_that_plans_every_k_steps) {
  scenario s = crossing(true);
  s.duration = 0.5;
  s.planning_vehicles[0].planning_period = 5;
  simulation sim(s);
  const mm::maneuver given{-1.5, 0.0};
  sim.override_command(0, given);
  for (int k = 1; k < 10; ++k) {
    sim.step();
    const mm::maneuver applied{sim.state(0).acceleration, sim.state(0).curvature};
    if (k < 5) {
      EXPECT_FALSE(sim.planned_now(0)) << k;
      EXPECT_EQ(applied, given) << k;
    } else if (k == 5) {
      ASSERT_TRUE(sim.planned_now(0));
      EXPECT_EQ(applied, sim.last_plan(0)->result.command);  // its own decision again
    }
  }
}

TEST(simulation, a_command_from_outside_beyond_the_vehicle_s_limits_or_for_an_inactive_vehicle_is_refused) {
  scenario s = crossing(true);
  s.planning_vehicles[0].start_time = 0.5;
  simulation sim(s);
  const auto message = [&](mm::maneuver u) {
    try {
      sim.override_command(0, u);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({0.0, 0.0}), "override_command: planning vehicle \"A\" is not_started: only an active vehicle takes a command");
  while (sim.time() < 0.5 - 1e-9) sim.step();
  ASSERT_EQ(sim.state(0).status, agent_status::active);
  EXPECT_EQ(message({-9.0, 0.0}), "override_command: planning vehicle \"A\": acceleration = -9: expected from -7 to 3 [m/s²]");
  EXPECT_EQ(message({std::nan(""), 0.0}),
            "override_command: planning vehicle \"A\": acceleration = NaN: expected from -7 to 3 [m/s²]");
  // κ_max(v) = min(1/R_min, a_lat_max / v²) at A's 40 km/h.
  const double most = mm::max_curvature(sim.state(0).speed, s.planning_vehicles[0].limits);
  EXPECT_EQ(message({0.0, most}), "no error");
  EXPECT_NE(message({0.0, -1.01 * most}).find("curvature = -"), std::string::npos);
  EXPECT_NE(message({0.0, -1.01 * most}).find(" [1/m] at its speed of 11.1"), std::string::npos);
  EXPECT_THROW(sim.override_command(1, {0.0, 0.0}), std::out_of_range);  // B does not plan
}

TEST(simulation, planning_every_k_steps_holds_the_command_in_between) {
  scenario s = crossing(true);
  s.duration = 0.5;
  s.planning_vehicles[0].planning_period = 5;
  simulation sim(s, {true});
  std::size_t plans = 0;
  mm::maneuver held;
  run(sim, [&](const simulation& now) {
    if (now.ended()) return;
    EXPECT_EQ(now.planned_now(0), now.step_index() % 5 == 0) << now.step_index();
    const mm::maneuver applied{now.state(0).acceleration, now.state(0).curvature};
    if (now.planned_now(0)) {
      ++plans;
      held = applied;
      EXPECT_GT(now.last_plan(0)->cpu_time_us, 0.0);
    } else {
      EXPECT_EQ(applied, held);
    }
  });
  EXPECT_EQ(plans, 10U);
  const run_metrics m = sim.metrics(0);
  EXPECT_EQ(m.planning_steps, 10U);
  EXPECT_GT(m.cpu_median_us, 0.0);
  EXPECT_GE(m.cpu_p99_us, m.cpu_median_us);
}

TEST(simulation, an_agent_that_reaches_the_end_of_its_path_leaves_and_the_run_ends) {
  scenario s;
  s.duration = 10.0;
  s.planning_vehicles.push_back(cruising("A", straight_path({0.0, 0.0}, 0.0, 20.0), 10.0));
  s.scripted_vehicles.push_back(scripted("B", straight_path({0.0, 10.0}, 0.0, 5.0), 10.0));
  simulation sim(s);
  while (sim.time() < 0.6 - 1e-9) sim.step();
  EXPECT_EQ(sim.state(1).status, agent_status::finished);
  EXPECT_FALSE(sim.state(1).present());
  EXPECT_TRUE(sim.planning_input(0)->obstacles.empty());
  run(sim);
  EXPECT_EQ(sim.state(0).status, agent_status::finished);
  EXPECT_NEAR(sim.time(), 2.0, 0.011);
}

TEST(simulation, agents_before_their_start_time_are_absent_or_wait_at_their_start) {
  scenario s;
  s.duration = 3.0;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 100.0), 0.0);
  a.avoidance = false;
  s.planning_vehicles.push_back(a);
  scripted_vehicle absent = scripted("late", straight_path({10.0, 10.0}, 0.0, 50.0), 5.0);
  absent.motion.start_time = 1.0;
  scripted_vehicle waiting = absent;
  waiting.name = "waiting";
  waiting.motion.path = straight_path({10.0, -10.0}, 0.0, 50.0);
  waiting.motion.before_start = before_start_behaviour::wait;
  s.scripted_vehicles = {absent, waiting};
  simulation sim(s);
  sim.step();
  EXPECT_EQ(sim.state(1).status, agent_status::not_started);
  EXPECT_EQ(sim.state(2).status, agent_status::waiting);
  EXPECT_EQ(sim.state(2).speed, 0.0);
  ASSERT_EQ(sim.planning_input(0)->obstacles.size(), 1U);  // only the waiting one is seen
  EXPECT_EQ(sim.planning_input(0)->obstacles[0].id, 2U);
  while (sim.time() < 2.0 - 1e-9) sim.step();
  EXPECT_EQ(sim.state(1).status, agent_status::active);
  EXPECT_NEAR(sim.state(1).pose.position.x, 15.0, 1e-9);  // 1 s after its start at 5 m/s
  EXPECT_NEAR(sim.state(2).pose.position.x, 15.0, 1e-9);
  EXPECT_EQ(sim.planning_input(0)->obstacles.size(), 2U);
}

TEST(simulation, a_pedestrian_waits_at_the_kerb_and_a_static_obstacle_is_seen_from_the_start) {
  scenario s;
  s.duration = 6.0;
  planning_vehicle a = cruising("A", straight_path({-10.0, 0.0}, 0.0, 100.0), 0.0);
  a.start_arc_length = 10.0;
  a.avoidance = false;
  s.planning_vehicles.push_back(a);
  pedestrian p;
  p.name = "P";
  p.motion.path = straight_path({1.0, -10.0}, pi / 2.0, 20.0);  // crossing northwards at x = 1
  p.motion.speed = speed_profile::constant(1.4);
  p.motion.stop = stop_rule{7.0, std::nullopt};  // the kerb at y = −3, reached after 5 s
  s.pedestrians.push_back(p);
  s.static_obstacles.push_back({"box", {{-12.0, 2.0}, {-10.0, 2.0}, {-10.0, 4.0}, {-12.0, 4.0}}});
  simulation sim(s);
  const mm::plan_input first = *sim.planning_input(0);
  ASSERT_EQ(first.obstacles.size(), 1U);  // the box needs one observation, P two
  EXPECT_EQ(first.obstacles[0].kind, mm::obstacle_kind::static_obstacle);
  EXPECT_EQ(first.obstacles[0].history.back().pose.position, (mm::vec2{-11.0, 3.0}));
  EXPECT_EQ(std::get<mm::convex_polygon>(first.obstacles[0].shape).vertices[0], (mm::vec2{-1.0, -1.0}));
  run(sim);
  EXPECT_EQ(sim.state(1).status, agent_status::stopped);
  EXPECT_DOUBLE_EQ(sim.state(1).speed, 0.0);
  EXPECT_NEAR(sim.state(1).pose.position.y, -3.0, 1e-12);
  const mm::plan_input last = *sim.planning_input(0);
  ASSERT_EQ(last.obstacles.size(), 2U);  // in id order: P (1), then the box (2)
  EXPECT_EQ(last.obstacles[0].id, 1U);
  EXPECT_EQ(last.obstacles[0].kind, mm::obstacle_kind::pedestrian);
  EXPECT_DOUBLE_EQ(last.obstacles[0].history.back().speed, 0.0);
  EXPECT_FALSE(sim.metrics(0).crash);
  EXPECT_NEAR(*sim.metrics(0).min_dist_m, 3.0 - 0.9 - 0.35, 1e-9);  // P at (1, −3), A's side at y = −0.9
}

TEST(simulation, scenario_validation_names_the_agent_and_the_field) {
  scenario s = crossing(true);
  EXPECT_FALSE(validation_error(s).has_value());

  scenario bad_speed = s;
  bad_speed.planning_vehicles[0].desired_speed = -1.0;
  EXPECT_EQ(validation_error(bad_speed).value(),
            "planning_vehicles[0] \"A\": desired_speed = -1: expected a finite number ≥ 0 [m/s]");
  EXPECT_THROW(simulation{bad_speed}, std::invalid_argument);

  scenario endless = s;
  endless.duration = 1e300;  // its step count would overflow
  EXPECT_EQ(validation_error(endless).value(),
            "scenario: duration = 1e+300: expected at most 10^7 time steps of 0.01 s (1e+05 s)");
  EXPECT_THROW(simulation{endless}, std::invalid_argument);
  endless.duration = 1e5;  // exactly 10^7 steps
  EXPECT_FALSE(validation_error(endless).has_value());

  scenario long_memory = s;
  long_memory.planning_vehicles[0].planner.history_window = 10.5;  // tracks of 1050 observations
  EXPECT_EQ(validation_error(long_memory).value(),
            "planning_vehicles[0] \"A\": planner.history_window = 10.5: expected at most 1000 time steps of 0.01 s "
            "(10 s), the longest track the simulator keeps");
  EXPECT_THROW(simulation{long_memory}, std::invalid_argument);
  long_memory.planning_vehicles[0].planner.history_window = 10.0;
  EXPECT_FALSE(validation_error(long_memory).has_value());

  scenario same_name = s;
  same_name.scripted_vehicles[0].name = "A";
  EXPECT_NE(validation_error(same_name).value().find("scripted_vehicles[0] \"A\": name"), std::string::npos);

  scenario bad_limit = s;
  bad_limit.planning_vehicles[0].limits.max_deceleration = 0.0;
  EXPECT_EQ(validation_error(bad_limit).value().rfind("planning_vehicles[0] \"A\": limits.max_deceleration = 0", 0), 0U);

  scenario bad_policy = s;
  bad_policy.planning_vehicles[0].planner.policy = {mm::forecast_policy_kind::constant, 0.3};
  EXPECT_EQ(validation_error(bad_policy).value().rfind("planning_vehicles[0] \"A\": planner.policy.constant_forecast_time", 0),
            0U);

  scenario beyond_path = s;
  beyond_path.scripted_vehicles[0].motion.start_arc_length = 150.0;
  EXPECT_EQ(validation_error(beyond_path).value().rfind("scripted_vehicles[0] \"B\": motion.start_arc_length = 150", 0),
            0U);

  scenario bad_stop = s;
  bad_stop.scripted_vehicles[0].motion.stop = stop_rule{10.0, 0.0};
  EXPECT_EQ(validation_error(bad_stop).value(),
            "scripted_vehicles[0] \"B\": motion.stop.duration = 0: expected a positive finite number [s]");

  scenario concave = s;
  concave.static_obstacles.push_back({"L", {{0.0, 0.0}, {2.0, 0.0}, {1.0, 0.2}, {1.0, 2.0}}});
  EXPECT_EQ(validation_error(concave).value().rfind("static_obstacles[0] \"L\": vertices: ", 0), 0U);

  scenario no_path = s;
  no_path.pedestrians.push_back({"P", {}, 0.35});
  EXPECT_EQ(validation_error(no_path).value(), "pedestrians[0] \"P\": motion.path: the path is empty");

  scenario bad_step = s;
  bad_step.time_step = 0.0;
  EXPECT_EQ(validation_error(bad_step).value(), "scenario: time_step = 0: expected a positive finite number [s]");
}

TEST(simulation, scenario_validation_keeps_every_road_user_within_what_the_planner_takes) {
  // Sizes, speeds, places and noise the planner would refuse at some step (mm::validation_error's
  // bounds) are refused before the run, naming the agent and the field.
  const scenario s = crossing(true);
  const auto error_of = [](const scenario& bad) { return validation_error(bad).value_or("(valid)"); };

  scenario huge = s;
  huge.scripted_vehicles[0].shape = mm::rectangle{4.5, 2e3};
  EXPECT_EQ(error_of(huge), "scripted_vehicles[0] \"B\": shape: rectangle width must be a positive number of metres "
                            "up to 1000, got 2000");
  scenario giant = s;
  giant.pedestrians.push_back({"P", scripted("P", straight_path({0.0, 5.0}, 0.0, 10.0), 1.0).motion, 5e3});
  EXPECT_EQ(error_of(giant), "pedestrians[0] \"P\": radius: disc radius must be a positive number of metres up to "
                             "1000, got 5000");

  scenario far = s;
  far.scripted_vehicles[0].motion.path = straight_path({3e7, 0.0}, 0.0, 2e7);
  EXPECT_EQ(error_of(far), "scripted_vehicles[0] \"B\": motion.path: a segment from (3e+07, 0) m of length 2e+07 m "
                           "reaches beyond ±4e+07 m: road users must stay within the ±1e+08 m the planner takes");

  scenario aside = s;
  aside.planning_vehicles[0].start_lateral_offset = 2e3;
  EXPECT_EQ(error_of(aside), "planning_vehicles[0] \"A\": start_lateral_offset = 2000: expected a finite offset within "
                             "±1000 [m]");

  scenario fast = s;
  fast.scripted_vehicles[0].motion.speed = speed_profile::constant(150.0);
  EXPECT_EQ(error_of(fast), "scripted_vehicles[0] \"B\": motion.speed.knots[0].speed = 150: expected at most 100 m/s");

  scenario long_drive = s;
  long_drive.duration = 1e5;
  long_drive.planning_vehicles[0].limits.speed_cap = 600.0;  // 6e7 m in the run
  EXPECT_EQ(error_of(long_drive), "planning_vehicles[0] \"A\": limits.speed_cap = 600: expected a speed at which the "
                                  "run's 1e+05 s cover at most 5e+07 m, so that road users stay within the ±1e+08 m the "
                                  "planner takes");
  long_drive.planning_vehicles[0].limits.speed_cap = 500.0;  // exactly 5e7 m
  EXPECT_EQ(error_of(long_drive), "(valid)");

  scenario noisy = s;
  noisy.noise.speed_sd = 11.0;
  EXPECT_EQ(error_of(noisy), "scenario: noise.speed_sd = 11: expected at most 10 m/s");
  noisy.noise = {10.0, 1.0, 10.0};
  EXPECT_EQ(error_of(noisy), "(valid)");

  scenario remote = s;
  remote.static_obstacles.push_back({"L", {{2e8, 0.0}, {2e8 + 2.0, 0.0}, {2e8, 2.0}}});
  EXPECT_EQ(error_of(remote), "static_obstacles[0] \"L\": vertices[0].x = 2e+08: expected a finite coordinate "
                              "within ±1e+08 [m]");
}

}  // namespace

namespace mm::sim {
namespace {

/// Six planning vehicles on two crossing roads, three each way, with noisy sensing.
scenario six_crossing_vehicles() {
  scenario s;
  s.name = "six";
  s.duration = testing::sanitize_scale() ? 0.3 : 1.0;
  s.seed = 7;
  s.noise = {0.05, 0.01, 0.1};
  for (int k = 0; k < 3; ++k) {
    const double back = 12.0 * k;
    s.planning_vehicles.push_back(
        testing::cruising(("E" + std::to_string(k)).c_str(), testing::straight_path({-30.0 - back, -1.75}, 0.0, 200.0), 9.0));
    s.planning_vehicles.push_back(testing::cruising(("N" + std::to_string(k)).c_str(),
                                                    testing::straight_path({1.75, -28.0 - back}, std::numbers::pi / 2.0, 200.0),
                                                    8.0));
  }
  for (planning_vehicle& v : s.planning_vehicles) v.planning_period = 5;
  return s;
}

/// Appends the state of every agent at `s`'s instant to `values`.
void append_states(const simulation& s, std::vector<double>& values) {
  for (const agent_state& a : s.states()) {
    values.insert(values.end(), {a.pose.position.x, a.pose.position.y, a.pose.heading, a.speed, a.acceleration, a.curvature});
  }
}

/// Calls `each` with the result of every plan made at `s`'s instant.
template <class Each>
void for_each_plan_now(const simulation& s, Each&& each) {
  for (agent_id id = 0; id < s.planning_vehicle_count(); ++id) {
    if (const plan_record* p = s.last_plan(id); p != nullptr && s.planned_now(id)) each(p->result);
  }
}

TEST(simulation, planning_the_vehicles_of_a_step_on_several_threads_gives_bit_identical_runs) {
  const auto record = [](std::size_t jobs) {
    simulation sim(six_crossing_vehicles(), run_options{false, jobs});
    std::vector<double> values;
    run(sim, [&](const simulation& s) {
      append_states(s, values);
      for_each_plan_now(s, [&](const mm::plan_result& r) {
        values.insert(values.end(), r.mi_brake.begin(), r.mi_brake.end());
        values.insert(values.end(), r.mi_accelerate.begin(), r.mi_accelerate.end());
        values.push_back(r.time_to_collision);
      });
    });
    return values;
  };
  const std::vector<double> one = record(1);
  const std::vector<double> two = record(2);
  const std::vector<double> three = record(3);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), three.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    // Bit for bit (NaN-free: infinite TTCs compare equal).
    ASSERT_EQ(one[i], two[i]) << "value " << i;
    ASSERT_EQ(one[i], three[i]) << "value " << i;
  }
}

TEST(simulation, with_exact_sensing_the_inputs_carry_the_motion_each_history_gives) {
  // Every observer of a road user estimates the same motion from the same observations: the
  // simulator estimates it once and hands it over; it must be what the planner would estimate.
  scenario s = six_crossing_vehicles();
  s.noise = {};
  simulation sim(s);
  std::size_t given = 0;
  std::size_t tracks = 0;
  while (!sim.ended()) {
    sim.step();
    for (agent_id id = 0; id < sim.planning_vehicle_count(); ++id) {
      const std::optional<mm::plan_input> input = sim.planning_input(id);
      if (!input) continue;
      for (const mm::obstacle_track& track : input->obstacles) {
        ++tracks;
        if (!track.motion) continue;
        ++given;
        mm::obstacle_track bare = track;
        bare.motion.reset();
        const mm::motion_estimate own = mm::estimate_motion(bare, input->config.history_window, input->time);
        ASSERT_TRUE(own.pose.position == track.motion->pose.position && own.pose.heading == track.motion->pose.heading &&
                    own.speed == track.motion->speed && own.yaw_rate == track.motion->yaw_rate)
            << "vehicle " << id << ", target " << track.id << " at " << input->time << " s";
      }
    }
  }
  EXPECT_GT(given, tracks / 2) << "most tracks should carry the shared estimate";
}

TEST(simulation, a_run_without_the_map_columns_makes_the_same_decisions_bit_for_bit) {
  const auto record = [](bool map_columns) {
    run_options options;
    options.map_columns = map_columns;
    simulation sim(six_crossing_vehicles(), options);
    std::vector<double> values;
    std::size_t columns = 0;
    run(sim, [&](const simulation& s) {
      append_states(s, values);
      for_each_plan_now(s, [&](const mm::plan_result& r) {
        values.insert(values.end(), {r.forecast_time, r.mi_brake_selected, r.mi_accelerate_selected, r.time_to_collision,
                                     static_cast<double>(r.mode), static_cast<double>(r.selected_family)});
        columns += r.mi_brake.size();
      });
    });
    return std::pair(values, columns);
  };
  const auto [with_map, columns] = record(true);
  const auto [without_map, none] = record(false);
  EXPECT_GT(columns, 0u);
  EXPECT_EQ(none, 0u) << "no column is computed without the map";
  ASSERT_EQ(with_map.size(), without_map.size());
  for (std::size_t i = 0; i < with_map.size(); ++i) ASSERT_EQ(with_map[i], without_map[i]) << "value " << i;
}

TEST(simulation, a_run_that_decides_only_the_commands_moves_every_agent_the_same_bit_for_bit) {
  const auto record = [](bool decision_only) {
    run_options options;
    options.map_columns = false;
    options.decision_only = decision_only;
    // The vehicles' own planner.decision_only is not read: the run option alone decides.
    scenario crossing = six_crossing_vehicles();
    for (planning_vehicle& v : crossing.planning_vehicles) v.planner.decision_only = !decision_only;
    simulation sim(crossing, options);
    std::vector<double> values;
    std::size_t without_indices = 0;
    std::size_t plans = 0;
    run(sim, [&](const simulation& s) {
      append_states(s, values);
      for_each_plan_now(s, [&](const mm::plan_result& r) {
        values.insert(values.end(), {r.time_to_collision, static_cast<double>(r.mode)});
        without_indices += r.indices_computed ? 0 : 1;
        ++plans;
      });
    });
    std::vector<run_metrics> metrics = sim.all_metrics();
    for (const run_metrics& m : metrics) {
      values.insert(values.end(), {m.time_in_brake_s, m.time_in_accel_s, m.min_dist_m.value_or(-1.0), m.max_speed_kmh});
    }
    return std::tuple(values, without_indices, plans);
  };
  const auto [full, none, plans] = record(false);
  const auto [lean, shortcuts, lean_plans] = record(true);
  EXPECT_EQ(none, 0u);
  EXPECT_EQ(plans, lean_plans);
  EXPECT_GT(shortcuts, plans / 20) << "some steps should be decided without the indices, or this test checks little";
  EXPECT_LT(shortcuts, plans) << "some steps should need the indices";
  ASSERT_EQ(full.size(), lean.size());
  for (std::size_t i = 0; i < full.size(); ++i) ASSERT_EQ(full[i], lean[i]) << "value " << i;
}

}  // namespace
}  // namespace mm::sim

TEST(simulation, a_desired_speed_profile_replaces_the_constant_desired_speed_from_the_vehicles_start) {
  scenario s;
  s.duration = 9.0;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 200.0), 10.0);
  a.avoidance = false;
  a.start_time = 1.0;
  a.desired_speed = 20.0;  // not used: the profile says 10 m/s until 2 s after the start, then 4 m/s from 3 s
  a.desired_speed_profile = speed_profile{{{0.0, 10.0}, {2.0, 10.0}, {3.0, 4.0}}};
  s.planning_vehicles.push_back(a);
  simulation sim(s);
  while (sim.time() < 2.5 - 1e-9) sim.step();
  EXPECT_NEAR(sim.state(0).speed, 10.0, 1e-9) << "1.5 s after its start the profile still says 10 m/s";
  while (!sim.ended()) sim.step();
  EXPECT_NEAR(sim.state(0).speed, 4.0, 0.05) << "the speed keeping has followed the profile down";

  scenario bad = s;
  bad.planning_vehicles[0].desired_speed_profile = speed_profile{{{1.0, 5.0}, {1.0, 6.0}}};
  const auto error = validation_error(bad);
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("desired_speed_profile.knots[1].time = 1: expected a time after the previous knot's 1 s"),
            std::string::npos)
      << *error;
}
