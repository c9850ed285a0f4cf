// Measuring recorded road users: what the planner is given at each recorded step, that the kept
// planner gives what `mm::plan` gives, and that a road user crossing close ahead takes room away.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "mm/commonroad/measure.hpp"

namespace {

using namespace mm::commonroad;

/// A road user moving at constant speed `v` [m/s] and yaw rate `omega` [rad/s] from `start`,
/// recorded at steps first..last.
obstacle recorded(std::uint32_t id, const std::string& type, mm::pose start, double v, double omega, std::int64_t first,
                  std::int64_t last, double dt, mm::footprint shape = mm::rectangle{4.5, 1.8}) {
  obstacle o;
  o.id = id;
  o.type = type;
  o.shape = shape;
  mm::pose p = start;
  for (std::int64_t k = first; k <= last; ++k) {
    o.states.push_back({k, p.position, p.heading, v, std::nullopt, std::nullopt});
    // Exact motion on the arc (or line) over one step.
    const double psi = p.heading + omega * dt;
    if (omega == 0.0) {
      p.position = {p.position.x + v * dt * std::cos(p.heading), p.position.y + v * dt * std::sin(p.heading)};
    } else {
      const double r = v / omega;
      p.position = {p.position.x + r * (std::sin(psi) - std::sin(p.heading)),
                    p.position.y - r * (std::cos(psi) - std::cos(p.heading))};
    }
    p.heading = psi;
  }
  return o;
}

/// Ego 1 drives east at 10 m/s from (0, 0), steps 0–30 at 0.1 s; car 2 drives north and crosses
/// 25 m ahead of it at t = 2.5 s; pedestrian 3 walks far away; car 4 appears at step 5; car 5
/// leaves after step 10; a parked car 6 stands 60 m behind.
scenario crossing() {
  scenario s;
  s.version = "2020a";
  s.time_step = 0.1;
  s.obstacles.push_back(recorded(1, "car", {{0, 0}, 0.0}, 10.0, 0.0, 0, 30, 0.1));
  s.obstacles.push_back(recorded(2, "car", {{25, -25}, std::numbers::pi / 2}, 10.0, 0.0, 0, 30, 0.1));
  s.obstacles.push_back(recorded(3, "pedestrian", {{-40, 40}, 0.0}, 1.4, 0.0, 0, 30, 0.1, mm::disc{0.3}));
  s.obstacles.push_back(recorded(4, "car", {{-80, 3.5}, 0.0}, 10.0, 0.0, 5, 30, 0.1));
  s.obstacles.push_back(recorded(5, "truck", {{-80, -3.5}, 0.0}, 10.0, 0.0, 0, 10, 0.1));
  obstacle parked;
  parked.id = 6;
  parked.role = obstacle_role::static_obstacle;
  parked.type = "parkedVehicle";
  parked.shape = mm::rectangle{4.5, 2.0};
  parked.states.push_back({0, {-60, 0}, 7.0, 0.0, std::nullopt, std::nullopt});
  s.obstacles.push_back(parked);
  s.planning_problems.push_back({100, {0, {0, 0}, 0.0, 10.0, std::nullopt, std::nullopt}});
  return s;
}

measure_options of(std::uint32_t agent) {
  measure_options o;
  o.agent = agent;
  return o;
}

std::vector<std::uint32_t> ids_at(const scenario& s, std::int64_t step) {
  std::vector<std::uint32_t> ids;
  planning_input(s, of(1), step, &ids);
  return ids;
}

TEST(measure, the_input_holds_the_recorded_ego_and_every_obstacle_present_then) {
  const scenario s = crossing();
  // Car 4 appears at step 5, truck 5 leaves after step 10.
  EXPECT_EQ(ids_at(s, 0), (std::vector<std::uint32_t>{2, 3, 5, 6}));
  EXPECT_EQ(ids_at(s, 4), (std::vector<std::uint32_t>{2, 3, 5, 6}));
  EXPECT_EQ(ids_at(s, 5), (std::vector<std::uint32_t>{2, 3, 4, 5, 6}));
  EXPECT_EQ(ids_at(s, 10), (std::vector<std::uint32_t>{2, 3, 4, 5, 6}));
  EXPECT_EQ(ids_at(s, 11), (std::vector<std::uint32_t>{2, 3, 4, 6}));

  // At its first state a road user comes with its recorded motion, as nothing can be estimated yet.
  scenario turning = crossing();
  turning.obstacles[3].states.front().yaw_rate = 0.2;
  const mm::plan_input first = planning_input(turning, of(1), 5);
  const mm::obstacle_track& appearing = first.obstacles[2];
  ASSERT_EQ(appearing.id, 4U);
  ASSERT_EQ(appearing.history.size(), 1U);
  ASSERT_TRUE(appearing.motion.has_value());
  EXPECT_EQ(appearing.motion->speed, 10.0);
  EXPECT_EQ(appearing.motion->yaw_rate, 0.2);
  EXPECT_EQ(appearing.motion->pose.position, (mm::vec2{-80, 3.5}));
  EXPECT_FALSE(mm::validation_error(first).has_value());
  EXPECT_FALSE(planning_input(turning, of(1), 6).obstacles[2].motion.has_value());  // estimated from two

  std::vector<std::uint32_t> ids;
  const mm::plan_input in = planning_input(s, of(1), 10, &ids);
  EXPECT_DOUBLE_EQ(in.time, 1.0);
  EXPECT_NEAR(in.ego.pose.position.x, 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(in.ego.speed, 10.0);
  ASSERT_EQ(in.obstacles.size(), ids.size());
  for (std::size_t j = 0; j < ids.size(); ++j) EXPECT_EQ(in.obstacles[j].id, ids[j]);
  // Car 2: the observations within the half-second history window, the last at the planning time.
  const mm::obstacle_track& car = in.obstacles[0];
  ASSERT_EQ(car.history.size(), 6U);
  EXPECT_FALSE(car.motion.has_value());
  EXPECT_DOUBLE_EQ(car.history.front().time, 0.5);
  EXPECT_DOUBLE_EQ(car.history.back().time, 1.0);
  EXPECT_EQ(car.kind, mm::obstacle_kind::vehicle);
  EXPECT_EQ(in.obstacles[1].kind, mm::obstacle_kind::pedestrian);
  // The parked car: one observation at the planning time, its heading wrapped.
  const mm::obstacle_track& parked = in.obstacles.back();
  EXPECT_EQ(parked.kind, mm::obstacle_kind::static_obstacle);
  ASSERT_EQ(parked.history.size(), 1U);
  EXPECT_DOUBLE_EQ(parked.history[0].time, 1.0);
  EXPECT_NEAR(parked.history[0].pose.heading, 7.0 - 2.0 * std::numbers::pi, 1e-12);
  EXPECT_FALSE(mm::validation_error(in).has_value()) << *mm::validation_error(in);
}

TEST(measure, a_negative_recorded_speed_is_a_standstill_and_a_faster_one_raises_the_speed_cap) {
  scenario s = crossing();
  s.obstacles[0].states[3].velocity = -0.2;
  s.obstacles[0].states[4].velocity = 35.0;
  EXPECT_EQ(planning_input(s, of(1), 3).ego.speed, 0.0);
  const mm::plan_input fast = planning_input(s, of(1), 4);
  EXPECT_EQ(fast.ego.speed, 35.0);
  EXPECT_EQ(fast.ego.limits.speed_cap, 35.0);
  EXPECT_FALSE(mm::validation_error(fast).has_value());
}

TEST(measure, the_recorded_maneuver_is_the_finite_difference_of_speed_and_heading) {
  // 12 m/s on a circle of radius 40 m, speeding up by 0.1 m/s per step.
  obstacle o = recorded(1, "car", {{0, 0}, 0.3}, 12.0, 12.0 / 40.0, 0, 9, 0.1);
  for (std::size_t k = 0; k < o.states.size(); ++k) o.states[k].velocity = 12.0 + 0.1 * static_cast<double>(k);
  for (std::size_t k = 0; k < o.states.size(); ++k) {
    const mm::maneuver u = recorded_maneuver(o, k, 0.1);
    EXPECT_NEAR(u.acceleration, 1.0, 1e-9) << k;
    // Heading change over the chord: 1/R up to the chord's shortening, (Δψ/2)/sin(Δψ/2) − 1 < 1e-4.
    EXPECT_NEAR(u.curvature, 1.0 / 40.0, 1e-5) << k;
  }
  // A heading that jumps by 2π between two states (files do not wrap) is no turn.
  o.states[5].orientation += 2.0 * std::numbers::pi;
  EXPECT_NEAR(recorded_maneuver(o, 4, 0.1).curvature, 1.0 / 40.0, 1e-5);
  // Standing still: no curvature from the noise of the heading.
  obstacle standing = recorded(1, "car", {{0, 0}, 0.0}, 0.0, 0.0, 0, 3, 0.1);
  standing.states[1].orientation = 0.4;
  EXPECT_EQ(recorded_maneuver(standing, 0, 0.1).curvature, 0.0);
  EXPECT_EQ(recorded_maneuver(recorded(1, "car", {{0, 0}, 0.0}, 5.0, 0.0, 0, 0, 0.1), 0, 0.1), mm::maneuver{});
}

TEST(measure, every_step_gives_what_plan_gives_on_the_same_input) {
  const scenario s = crossing();
  const measurement m = measure(s, of(1));
  ASSERT_EQ(m.steps.size(), 31U);
  for (const measured_step& step : m.steps) {
    std::vector<std::uint32_t> ids;
    const mm::plan_result fresh = mm::plan(planning_input(s, of(1), step.step, &ids));
    EXPECT_EQ(ids, step.obstacle_ids);
    EXPECT_EQ(fresh.mi_brake, step.result.mi_brake) << step.time;
    EXPECT_EQ(fresh.mi_accelerate, step.result.mi_accelerate) << step.time;
    EXPECT_EQ(fresh.command, step.result.command) << step.time;
    EXPECT_EQ(fresh.mode, step.result.mode) << step.time;
  }
}

TEST(measure, a_road_user_crossing_close_ahead_takes_room_away_and_one_far_away_does_not) {
  const measurement near = measure(crossing(), of(1));
  double least = 1.0;
  bool unsafe = false;
  for (const measured_step& step : near.steps) {
    least = std::min(least, room(step.result));
    unsafe = unsafe || step.result.mode != mm::planning_mode::nominal;
  }
  EXPECT_LT(least, 0.9);
  EXPECT_TRUE(unsafe) << "driving on at 10 m/s into the crossing car must be unsafe at some step";

  scenario far = crossing();
  far.obstacles[1] = recorded(2, "car", {{25, -125}, std::numbers::pi / 2}, 10.0, 0.0, 0, 30, 0.1);
  for (const measured_step& step : measure(far, of(1)).steps) {
    EXPECT_EQ(room(step.result), 1.0) << step.time;
    EXPECT_EQ(step.result.mode, mm::planning_mode::nominal) << step.time;
  }
}

TEST(measure, on_its_lane_a_road_user_has_no_more_room_than_without_and_less_where_steering_leaves_the_lane) {
  // The crossing with two lanelets: the ego's 3.5 m lane along y = 0 and the crossing car's along
  // x = 25 (spec §5's road constraint on their union).
  scenario s = crossing();
  s.lanelets.push_back({10, {{-100, 1.75}, {200, 1.75}}, {{-100, -1.75}, {200, -1.75}}, {}, {}});
  s.lanelets.push_back({11, {{23.25, -100}, {23.25, 100}}, {{26.75, -100}, {26.75, 100}}, {}, {}});
  measure_options on_lane = of(1);
  on_lane.drivable_area = std::make_shared<const mm::drivable_area>(lanelet_polygons(s));
  const measurement open = measure(s, of(1));
  const measurement road = measure(s, on_lane);
  ASSERT_EQ(open.steps.size(), road.steps.size());
  std::size_t less = 0;
  for (std::size_t k = 0; k < road.steps.size(); ++k) {
    EXPECT_TRUE(road.steps[k].result.on_drivable_area) << road.steps[k].time;
    EXPECT_FALSE(open.steps[k].result.on_drivable_area);
    // The road only takes room (up to the interpolation's rounding, docs/method.md §5).
    EXPECT_LE(room(road.steps[k].result), room(open.steps[k].result) + 1e-4) << road.steps[k].time;
    less += room(road.steps[k].result) < room(open.steps[k].result) - 0.05 ? 1 : 0;
  }
  EXPECT_GT(less, road.steps.size() / 2) << "a 3.5 m lane leaves a car little room to steer within 1 s";
}

TEST(measure, pedestrians_static_obstacles_and_unknown_ids_cannot_be_measured_and_the_message_says_what_can) {
  const scenario s = crossing();
  for (const std::uint32_t id : {3U, 6U, 77U}) {
    try {
      measure(s, of(id));
      ADD_FAILURE() << id;
    } catch (const measure_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("road user " + std::to_string(id)), std::string::npos) << message;
      EXPECT_NE(message.find("the road users the planner can take the place of (measure, replay) are: 1, 2, 4, 5"), std::string::npos) << message;
    }
  }
  EXPECT_THROW(planning_input(s, of(4), 2), measure_error);  // car 4 appears at step 5
}

TEST(measure, the_list_of_road_users_that_can_be_measured_stops_after_twenty_and_says_how_many_there_are) {
  scenario s = crossing();
  EXPECT_EQ(measurable_road_users_text(s), "1, 2, 4, 5");
  for (std::uint32_t id = 10; id < 30; ++id) {
    s.obstacles.push_back(recorded(id, "car", {{-80, 7.0 + id}, 0.0}, 10.0, 0.0, 0, 30, 0.1));
  }
  // 24 in all: 1, 2, 4, 5 and 10–29.
  const std::string text = measurable_road_users_text(s);
  EXPECT_EQ(text.rfind("1, 2, 4, 5, 10, 11, ", 0), 0U) << text;
  EXPECT_NE(text.find(", 25, … (24 in all)"), std::string::npos) << text;
  EXPECT_EQ(text.find("26"), std::string::npos) << text;

  scenario walkers;
  walkers.time_step = 0.1;
  walkers.obstacles.push_back(recorded(3, "pedestrian", {{-40, 40}, 0.0}, 1.4, 0.0, 0, 30, 0.1, mm::disc{0.3}));
  EXPECT_EQ(measurable_road_users_text(walkers), "none");
}

TEST(measure, the_recorded_ego_is_the_obstacle_with_the_problem_s_id_its_id_minus_90000_or_the_one_at_its_start) {
  scenario s = crossing();
  EXPECT_EQ(recorded_ego(s, s.planning_problems[0]), 1U);  // at its start
  planning_problem same_id = s.planning_problems[0];
  same_id.id = 2;
  EXPECT_EQ(recorded_ego(s, same_id), 2U);
  planning_problem ind = s.planning_problems[0];
  ind.id = 90004;
  EXPECT_EQ(recorded_ego(s, ind), 4U);
  planning_problem elsewhere = s.planning_problems[0];
  elsewhere.initial.position = {500, 500};
  EXPECT_EQ(recorded_ego(s, elsewhere), std::nullopt);
  planning_problem pedestrian = s.planning_problems[0];
  pedestrian.id = 3;
  pedestrian.initial.position = {500, 500};
  EXPECT_EQ(recorded_ego(s, pedestrian), std::nullopt);
}

}  // namespace
