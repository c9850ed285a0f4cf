// Replaying a recording with one road user driven by the planner: the others are where they were
// recorded, the driven one starts as recorded and follows its path, and the loop is closed (it brakes
// for what it would have hit).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/replay.hpp"
#include "mm/sim/simulation.hpp"

namespace {

using namespace mm::commonroad;

state at(std::int64_t step, mm::vec2 position, double heading, double speed) {
  return {step, position, heading, speed, std::nullopt, std::nullopt};
}

/// A road user recorded at steps first.. with the given speeds [m/s] (one per step) and a constant
/// yaw rate `omega` [rad/s], from `start`, at 0.1 s steps: it moves v_k·Δt along its heading.
obstacle recorded(std::uint32_t id, const std::string& type, mm::pose start, const std::vector<double>& speeds,
                  double omega, std::int64_t first, mm::footprint shape = mm::rectangle{4.5, 1.8}) {
  obstacle o;
  o.id = id;
  o.type = type;
  o.shape = shape;
  mm::pose p = start;
  for (std::size_t k = 0; k < speeds.size(); ++k) {
    o.states.push_back(at(first + static_cast<std::int64_t>(k), p.position, p.heading, speeds[k]));
    p.position = {p.position.x + speeds[k] * 0.1 * std::cos(p.heading), p.position.y + speeds[k] * 0.1 * std::sin(p.heading)};
    p.heading += omega * 0.1;
  }
  return o;
}

std::vector<double> constant(double v, std::size_t n) { return std::vector<double>(n, v); }

/// Car 1 drives east at 10 m/s (steps 0–40); car 2 turns left while it slows from 8 to 2 m/s
/// (steps 5–30); pedestrian 3 walks, stops, walks (steps 0–40); car 4 stands, never moving (steps
/// 10–25).
scenario traffic() {
  scenario s;
  s.benchmark_id = "TEST_Replay-1";
  s.version = "2020a";
  s.time_step = 0.1;
  s.obstacles.push_back(recorded(1, "car", {{0, 0}, 0.0}, constant(10.0, 41), 0.0, 0));
  std::vector<double> slowing;
  for (int k = 0; k <= 25; ++k) slowing.push_back(8.0 - 0.24 * k);
  s.obstacles.push_back(recorded(2, "car", {{40, -30}, std::numbers::pi / 2}, slowing, 0.3, 5));
  std::vector<double> walking = constant(1.4, 41);
  for (std::size_t k = 15; k < 25; ++k) walking[k] = 0.0;
  s.obstacles.push_back(recorded(3, "pedestrian", {{-30, 20}, -0.5}, walking, 0.0, 0, mm::disc{0.3}));
  s.obstacles.push_back(recorded(4, "car", {{-50, -10}, 1.0}, constant(0.0, 16), 0.0, 10));
  s.planning_problems.push_back({100, at(0, {0, 0}, 0.0, 10.0)});
  return s;
}

/// Runs `sc` and calls `check(sim)` at every step.
template <class F>
void run(const mm::sim::scenario& sc, F check) {
  mm::sim::simulation sim(sc);
  check(sim);
  while (!sim.ended()) {
    sim.step();
    check(sim);
  }
}

TEST(replay, every_replayed_road_user_is_where_it_was_recorded_at_every_recorded_step_and_absent_outside_them) {
  const scenario s = traffic();
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  const mm::sim::scenario sc = replay_scenario(s, options);
  ASSERT_EQ(sc.planning_vehicles.size(), 1U);
  ASSERT_EQ(sc.scripted_vehicles.size(), 2U);
  ASSERT_EQ(sc.pedestrians.size(), 1U);
  EXPECT_TRUE(sc.static_obstacles.empty());
  EXPECT_EQ(sc.scripted_vehicles[0].name, "car-2");
  EXPECT_EQ(sc.scripted_vehicles[1].name, "car-4");  // never moves: it stands for its recorded steps
  EXPECT_DOUBLE_EQ(sc.duration, 4.0);
  std::size_t checked = 0;
  run(sc, [&](const mm::sim::simulation& sim) {
    const long hundredths = std::lround(sim.time() * 100.0);
    for (const std::string name : {"car-2", "pedestrian-3", "car-4"}) {
      const obstacle& o = s.obstacles[name == "car-2" ? 1 : name == "pedestrian-3" ? 2 : 3];
      const mm::sim::agent_state& a = sim.state(*sim.find(name));
      const std::int64_t first = o.states.front().step;
      const std::int64_t last = o.states.back().step;
      if (hundredths < first * 10 || hundredths > last * 10) {
        EXPECT_FALSE(a.present()) << name << " at " << sim.time();
      }
      if (hundredths % 10 != 0 || hundredths < first * 10 || hundredths > last * 10) continue;
      const state& x = o.states[static_cast<std::size_t>(hundredths / 10 - first)];
      ASSERT_TRUE(a.present()) << name << " at " << sim.time();
      EXPECT_NEAR(a.pose.position.x, x.position.x, 1e-6) << name << " at " << sim.time();
      EXPECT_NEAR(a.pose.position.y, x.position.y, 1e-6) << name << " at " << sim.time();
      ++checked;
    }
  });
  EXPECT_EQ(checked, 26U + 41U + 16U);
}

/// Runs `sc` and checks at every step that each present road user of `names` reaches the speed its
/// state's acceleration gives over the step: v(t + Δt) = v(t) + a(t)·Δt. Returns the number of steps
/// on which a speed changed.
std::size_t check_speed_changes(const mm::sim::scenario& sc, const std::vector<std::string>& names) {
  std::vector<mm::sim::agent_state> before;
  std::size_t changing = 0;
  run(sc, [&](const mm::sim::simulation& sim) {
    for (const std::string& name : names) {
      const mm::sim::agent_id id = *sim.find(name);
      if (before.empty() || !before[id].present() || !sim.state(id).present()) continue;
      const mm::sim::agent_state& was = before[id];
      const mm::sim::agent_state& is = sim.state(id);
      EXPECT_NEAR(is.speed, was.speed + was.acceleration * sc.time_step, 1e-9) << name << " at " << sim.time() - sc.time_step;
      if (is.speed != was.speed) ++changing;
    }
    before.assign(sim.states().begin(), sim.states().end());
  });
  return changing;
}

TEST(replay, a_replayed_road_user_s_acceleration_is_its_speed_change_over_the_coming_step_also_when_it_reacts) {
  // The replay holds each recorded step's mean speed, so the speed jumps at the recorded steps (within
  // 10⁻⁷ s); the slope of the jump is not what the road user applies over a step of 0.01 s.
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  EXPECT_GT(check_speed_changes(replay_scenario(traffic(), options), {"car-2", "pedestrian-3"}), 10U);
  // Car 3 brakes behind car 1, which stops: it lags behind its recording.
  scenario s;
  s.version = "2020a";
  s.time_step = 0.1;
  s.obstacles.push_back(recorded(1, "car", {{0, 0}, 0.0}, constant(10.0, 51), 0.0, 0));
  s.obstacles.push_back(recorded(3, "car", {{-20, 0}, 0.0}, constant(10.0, 51), 0.0, 0));
  options.desired_speed = 0.0;
  options.reactive = reactive_traffic();
  EXPECT_GT(check_speed_changes(replay_scenario(s, options), {"car-3"}), 100U);
}

TEST(replay, the_driven_road_user_starts_as_recorded_and_without_avoidance_keeps_to_its_recorded_path) {
  scenario s = traffic();
  s.obstacles[0] = recorded(1, "car", {{0, 0}, 0.2}, constant(10.0, 41), 0.1, 3);  // a left curve, from step 3
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  const mm::sim::scenario sc = replay_scenario(s, options);
  const mm::sim::planning_vehicle& ego = sc.planning_vehicles.front();
  EXPECT_EQ(ego.name, "car-1");
  EXPECT_DOUBLE_EQ(ego.start_time, 0.30000000000000004);
  EXPECT_DOUBLE_EQ(ego.initial_speed, 10.0);
  ASSERT_TRUE(ego.desired_speed_profile.has_value());  // its recorded speeds, from its start
  EXPECT_EQ(ego.desired_speed_profile->knots.size(), 41U);
  EXPECT_DOUBLE_EQ(ego.desired_speed_profile->knots[40].time, 4.0);
  EXPECT_FALSE(ego.avoidance);
  bool started = false;
  double largest_offset = 0.0;
  run(sc, [&](const mm::sim::simulation& sim) {
    const mm::sim::agent_state& a = sim.state(0);
    if (!a.present()) return;
    if (!started) {
      started = true;
      EXPECT_NEAR(sim.time(), 0.3, 1e-9);
      EXPECT_NEAR(a.pose.position.x, 0.0, 1e-9);
      EXPECT_NEAR(a.pose.position.y, 0.0, 1e-9);
      EXPECT_DOUBLE_EQ(a.speed, 10.0);
    }
    largest_offset = std::max(largest_offset, std::abs(a.lateral_offset));
  });
  EXPECT_TRUE(started);
  EXPECT_LT(largest_offset, 0.1) << "pure pursuit along the polyline of its recorded positions";
}

TEST(replay, the_driven_road_user_keeps_the_speeds_it_was_recorded_at_unless_given_one) {
  scenario s = traffic();
  std::vector<double> slowing;
  for (int k = 0; k <= 40; ++k) slowing.push_back(k < 10 ? 10.0 : std::max(4.0, 10.0 - 0.6 * (k - 10)));
  s.obstacles[0] = recorded(1, "car", {{0, 0}, 0.0}, slowing, 0.0, 0);
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  mm::sim::simulation recorded_speeds(replay_scenario(s, options));
  mm::sim::run(recorded_speeds);
  // Its speed keeping (a P-controller with a gain of 1/s, docs/simulator.md) follows the driver's
  // slowing from 10 to 4 m/s with a lag.
  EXPECT_LT(recorded_speeds.state(0).speed, 6.0) << "it slowed down as its driver did";
  EXPECT_GT(recorded_speeds.state(0).speed, 4.0);
  options.desired_speed = 10.0;
  mm::sim::simulation constant_speed(replay_scenario(s, options));
  mm::sim::run(constant_speed);
  EXPECT_NEAR(constant_speed.state(0).speed, 10.0, 1e-9);
}

/// Car 1 recorded at 10 m/s from the origin east for 5 s, into car 2, parked 30 m ahead from step 0.
scenario towards_a_parked_car() {
  scenario s;
  s.version = "2020a";
  s.time_step = 0.1;
  s.obstacles.push_back(recorded(1, "car", {{0, 0}, 0.0}, constant(10.0, 51), 0.0, 0));
  obstacle parked;
  parked.id = 2;
  parked.role = obstacle_role::static_obstacle;
  parked.type = "parkedVehicle";
  parked.shape = mm::rectangle{4.5, 1.8};
  parked.states.push_back(at(0, {30, 0}, 0.0, 0.0));
  s.obstacles.push_back(parked);
  return s;
}

TEST(replay, the_loop_is_closed_the_planner_avoids_the_car_the_recorded_driver_ran_into) {
  // The recording: car 1 drives at 10 m/s into car 2, which stands 30 m ahead from step 0.
  scenario s = towards_a_parked_car();
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  {
    mm::sim::simulation sim(replay_scenario(s, options));
    mm::sim::run(sim);
    EXPECT_TRUE(sim.metrics(0).crash) << "without the planner it drives into the parked car, as recorded";
  }
  options.avoidance = true;
  mm::sim::simulation sim(replay_scenario(s, options));
  mm::sim::run(sim);
  const mm::sim::run_metrics m = sim.metrics(0);
  EXPECT_FALSE(m.crash);
  EXPECT_GT(m.planning_steps, 0U);
  EXPECT_GT(m.time_in_brake_s + m.time_in_accel_s, 0.0) << "it left nominal planning to avoid it";
}

TEST(replay, on_the_lanelets_the_replay_s_drivable_area_is_their_union_and_the_driven_car_keeps_to_its_lane) {
  // Car 1 at 10 m/s in a 3.5 m lane towards a car parked in the middle of it, 30 m ahead; beside
  // the lane, open ground. Off the lanelets the planner may swerve out of the lane; on them it must
  // stay in the lane, and brakes.
  scenario s = towards_a_parked_car();
  s.lanelets.push_back({5, {{-50, 1.75}, {150, 1.75}}, {{-50, -1.75}, {150, -1.75}}, {}, {}});
  replay_options options;
  options.agent = 1;
  options.on_lanelets = true;
  const mm::sim::scenario on_lane = replay_scenario(s, options);
  ASSERT_EQ(on_lane.drivable_area.polygons.size(), 1U);
  EXPECT_EQ(on_lane.drivable_area.open_edges.size(), 2U);
  options.on_lanelets = false;
  EXPECT_TRUE(replay_scenario(s, options).drivable_area.empty());
  mm::sim::simulation sim(on_lane);
  mm::sim::run(sim);
  const mm::sim::run_metrics m = sim.metrics(0);
  EXPECT_FALSE(m.crash);
  // Half the lane less half the car: 0.85 m to either side.
  EXPECT_LT(m.max_lateral_offset_m, 0.85);
  EXPECT_GT(m.time_in_brake_s, 0.0);
}

/// The message of the measure_error `replay_scenario(s, driven)` throws; "no measure_error" if it
/// throws none.
TEST(replay, a_reactive_replay_gives_car_following_to_every_other_moving_vehicle_and_to_no_one_else) {
  replay_options options;
  options.agent = 1;
  const mm::sim::scenario plain = replay_scenario(traffic(), options);
  options.reactive = mm::sim::scripted_car_following{};
  options.reactive->following.time_gap = 1.5;
  const mm::sim::scenario reactive = replay_scenario(traffic(), options);
  ASSERT_EQ(reactive.scripted_vehicles.size(), 2U);
  for (const mm::sim::scripted_vehicle& v : plain.scripted_vehicles) EXPECT_FALSE(v.car_following) << v.name;
  // Car 2 moves and follows; car 4 never moves (it stands where it was recorded); pedestrian 3
  // walks as recorded.
  EXPECT_EQ(reactive.scripted_vehicles[0].name, "car-2");
  ASSERT_TRUE(reactive.scripted_vehicles[0].car_following.has_value());
  EXPECT_EQ(reactive.scripted_vehicles[0].car_following->following.time_gap, 1.5);
  EXPECT_EQ(reactive.scripted_vehicles[1].name, "car-4");
  EXPECT_FALSE(reactive.scripted_vehicles[1].car_following.has_value());
  EXPECT_EQ(reactive.pedestrians.size(), 1U);
}

TEST(replay, in_a_reactive_replay_the_car_behind_brakes_for_the_driven_one_that_the_recorded_one_runs_into) {
  // Car 1 and car 3, 20 m behind it, recorded at 10 m/s east for 5 s. Car 1 is driven with a desired
  // speed of 0 and no planner: it brakes to a stop. Replayed as recorded, car 3 runs into it; in a
  // reactive replay it brakes behind it.
  scenario s;
  s.version = "2020a";
  s.time_step = 0.1;
  s.obstacles.push_back(recorded(1, "car", {{0, 0}, 0.0}, constant(10.0, 51), 0.0, 0));
  s.obstacles.push_back(recorded(3, "car", {{-20, 0}, 0.0}, constant(10.0, 51), 0.0, 0));
  replay_options options;
  options.agent = 1;
  options.avoidance = false;
  options.desired_speed = 0.0;
  const auto crash_of = [&](bool reactive) {
    options.reactive = reactive ? std::optional(reactive_traffic()) : std::nullopt;
    mm::sim::simulation sim(replay_scenario(s, options));
    mm::sim::run(sim);
    return sim.metrics(0);
  };
  const mm::sim::run_metrics recorded_behind = crash_of(false);
  EXPECT_TRUE(recorded_behind.crash);
  const mm::sim::run_metrics reacting_behind = crash_of(true);
  EXPECT_FALSE(reacting_behind.crash);
  EXPECT_GT(reacting_behind.min_dist_m.value(), 1.0);
}

std::string refusal(const scenario& s, std::uint32_t driven) {
  replay_options options;
  options.agent = driven;
  try {
    replay_scenario(s, options);
  } catch (const measure_error& e) {
    return e.what();
  }
  return "no measure_error";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(replay, a_road_user_that_cannot_be_driven_or_moved_is_refused_with_its_id_and_why) {
  const scenario s = traffic();
  EXPECT_PRED2(contains, refusal(s, 3), "road user 3: a pedestrian");
  EXPECT_PRED2(contains, refusal(s, 4), "road user 4 (car): it does not move");
  scenario polygon = traffic();
  polygon.obstacles[1].shape = mm::convex_polygon{{{-2, -1}, {3, -1}, {3, 1}, {-2, 1}}};
  EXPECT_PRED2(contains, refusal(polygon, 1), "road user 2 (car): a moving polygon");
  scenario tiny = traffic();
  tiny.obstacles[2].shape = mm::disc{0.01};
  EXPECT_PRED2(contains, refusal(tiny, 1),
               "road user 3 (pedestrian): its footprint is 0.02 m across: expected at least 0.05 m");
  scenario jump = traffic();
  jump.obstacles[1].states[10].position.x += 50.0;  // 500 m/s over one step, and back
  const std::string too_fast = refusal(jump, 1);
  EXPECT_PRED2(contains, too_fast, "road user 2 (car): it moves at");
  EXPECT_PRED2(contains, too_fast, "expected at most 100 m/s");
  scenario round = traffic();
  round.obstacles[0].shape = mm::disc{1.0};
  EXPECT_PRED2(contains, refusal(round, 1), "road user 1 (car): the planner drives a rectangular footprint");
  EXPECT_PRED2(contains, refusal(s, 99), "road user 99: no obstacle has this id");
  scenario ages = traffic();
  ages.time_step = 1e6;  // 40 steps of 11.6 days: more simulation steps than a run may take
  EXPECT_PRED2(contains, refusal(ages, 1),
               "the recording lasts 4e+07 s (timeStepSize 1e+06 s): expected at most 10^7 simulation steps of 0.01 s "
               "(100000 s) to replay");
}

}  // namespace
