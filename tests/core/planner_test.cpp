#include "mm/planner.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "mm/collision.hpp"
#include "mm/reference_planner.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

/// The ego driving east at `speed` from the origin, wanting to keep going straight.
plan_input ego_only(double speed) {
  plan_input in;
  in.time = 1.0;
  in.ego.pose = {{0.0, 0.0}, 0.0};
  in.ego.speed = speed;
  in.nominal = {0.0, 0.0};
  return in;
}

/// A vehicle observed for 0.5 s, now at `at`, moving with constant speed and yaw rate.
obstacle_track vehicle(std::uint32_t id, pose at, double speed, double yaw_rate, double now) {
  obstacle_track track;
  track.id = id;
  track.history = testing::ctrv_history(at, speed, yaw_rate, now);
  return track;
}

/// The ego at 40 km/h and a car from the north at 36 km/h, timed to collide (paper Fig. 1).
plan_input crossing_scene() {
  plan_input in = ego_only(40.0 / 3.6);
  in.obstacles.push_back(vehicle(1, {{22.0, 20.0}, -pi / 2.0}, 10.0, 0.0, in.time));
  return in;
}

void expect_all_room(const plan_result& r) {
  ASSERT_TRUE(r.ok()) << r.error;
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    EXPECT_EQ(r.mi_brake[i], 1.0) << i;
    EXPECT_EQ(r.mi_accelerate[i], 1.0) << i;
    EXPECT_EQ(r.excluded[i], 0) << i;
  }
  EXPECT_EQ(r.mode, planning_mode::nominal);
  EXPECT_EQ(r.time_to_collision, no_collision);
}

TEST(planner, without_obstacles_every_index_is_one_and_the_nominal_command_is_returned) {
  plan_input in = ego_only(12.0);
  in.nominal = {0.7, 0.01};
  const plan_result r = plan(in);
  expect_all_room(r);
  EXPECT_EQ(r.command, in.nominal);
  EXPECT_EQ(r.forecast_time, 0.0);
  ASSERT_EQ(r.forecast_times.size(), 17u);
  EXPECT_DOUBLE_EQ(r.forecast_times.back(), 2.0);
}

TEST(planner, a_far_obstacle_is_ignored_at_no_cost) {
  plan_input in = ego_only(12.0);
  in.obstacles.push_back(vehicle(7, {{300.0, 0.0}, pi}, 15.0, 0.0, in.time));
  const plan_result r = plan(in);
  expect_all_room(r);
  ASSERT_EQ(r.obstacles.size(), 1u);
  EXPECT_FALSE(r.obstacles[0].relevant);
  EXPECT_EQ(r.command, in.nominal);
}

TEST(planner, an_obstacle_driving_away_leaves_all_the_room) {
  plan_input in = ego_only(10.0);
  in.obstacles.push_back(vehicle(2, {{12.0, 0.0}, 0.0}, 20.0, 0.0, in.time));  // ahead, faster
  in.obstacles.push_back(vehicle(3, {{-5.0, 8.0}, 2.5}, 10.0, 0.0, in.time));  // behind-left, leaving
  const plan_result r = plan(in);
  EXPECT_TRUE(r.obstacles[0].relevant);
  expect_all_room(r);
  EXPECT_EQ(r.command, in.nominal);
}

TEST(planner, a_crossing_vehicle_forces_avoidance_with_a_safe_command) {
  const plan_input in = crossing_scene();
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_NE(r.mode, planning_mode::nominal);
  EXPECT_LT(r.time_to_collision, 3.0);
  EXPECT_GT(r.mi_brake[0], 0.0);
  EXPECT_LT(std::max(r.mi_brake[0], r.mi_accelerate[0]), 1.0);
  // The command is safe under the selected forecast.
  const forecast_obstacle b{r.obstacles[0].motion, rectangle{}};
  EXPECT_FALSE(maneuver_collides(in.ego, r.command, std::span(&b, 1), std::vector<double>{r.forecast_time},
                                 {1.0, 3.0, 0.01, 0.0}));
}

TEST(planner, the_fast_search_holds_an_obstacle_that_never_collides_at_the_first_forecast_time) {
  // Behind the ego, slower and turning: within reach, but no maneuver meets it under any forecast.
  const obstacle_track follower = vehicle(2, {{-16.0, -1.0}, 0.0}, 4.0, 0.3, 1.0);
  plan_input alone = ego_only(40.0 / 3.6);
  alone.obstacles.push_back(follower);
  const plan_result free = plan(alone);
  ASSERT_TRUE(free.ok()) << free.error;
  ASSERT_TRUE(free.obstacles[0].relevant);
  expect_all_room(free);

  // A car from the north, turning a little, timed to collide: its forecast time matters.
  plan_input in = ego_only(40.0 / 3.6);
  in.obstacles.push_back(vehicle(1, {{22.0, 20.0}, -pi / 2.0}, 10.0, 0.2, in.time));
  in.obstacles.push_back(follower);
  const plan_result fast = plan(in);
  in.config.assignment_search = assignment_search_kind::exhaustive;
  const plan_result exhaustive = plan(in);
  ASSERT_TRUE(fast.ok() && exhaustive.ok()) << fast.error << exhaustive.error;
  EXPECT_EQ(fast.obstacles[1].forecast_index, 0u);
  // Only the crossing car's forecast times were tried (searching the follower's too took 64).
  EXPECT_LE(fast.work.assignments_evaluated, fast.forecast_times.size());
  // The crossing car's forecast time is the exhaustive search's, and so is the room.
  EXPECT_EQ(fast.obstacles[0].forecast_index, exhaustive.obstacles[0].forecast_index);
  EXPECT_NEAR(std::max(fast.mi_brake_selected, fast.mi_accelerate_selected),
              std::max(exhaustive.mi_brake_selected, exhaustive.mi_accelerate_selected), 1e-3);
}

TEST(planner, the_fast_search_holds_an_obstacle_that_does_not_turn_at_the_first_forecast_time) {
  // Two turning cars and one going straight, from a random scene (planner_properties): the third's
  // clearances are the same under every forecast time. The search once left it at τ_9, where the
  // climb from the best common forecast time had put it.
  plan_input in = ego_only(6.3438337111893253);
  in.time = 5.4396078486842114;
  in.ego.pose = {{13.204015218757313, 32.454223024924516}, 1.0469288361970559};
  in.nominal = {0.18635707468596197, -0.0065757366397270253};
  in.obstacles.push_back(vehicle(1, {{36.170453933644708, 54.918530679431768}, -2.4926541139036456}, 9.8020980447677388,
                                 -0.28062679892815, in.time));
  in.obstacles.push_back(vehicle(2, {{17.800764894639538, 64.369612019356026}, -1.3936727006564296}, 11.692041613790883,
                                 -0.47506197695140, in.time));
  in.obstacles.push_back(vehicle(3, {{9.4172358201392186, 36.770643023234761}, 0.61415796012678836}, 4.7824192659832683,
                                 0.0, in.time));
  in.obstacles[0].shape = rectangle{3.7328799434860547, 1.8286305848242612};
  in.obstacles[1].shape = rectangle{4.5533023884136785, 1.6439936542261866};
  in.obstacles[2].shape = rectangle{4.7798562741097443, 1.7131324622221671};
  const plan_result fast = plan(in);
  in.config.assignment_search = assignment_search_kind::exhaustive;
  const plan_result exhaustive = plan(in);
  ASSERT_TRUE(fast.ok() && exhaustive.ok()) << fast.error << exhaustive.error;
  ASSERT_TRUE(fast.obstacles[2].relevant);
  ASSERT_EQ(fast.obstacles[2].motion.yaw_rate, 0.0);
  // Where the exhaustive search's tie rule puts it.
  EXPECT_EQ(exhaustive.obstacles[2].forecast_index, 0u);
  EXPECT_EQ(fast.obstacles[2].forecast_index, 0u);
  EXPECT_NEAR(std::max(fast.mi_brake_selected, fast.mi_accelerate_selected),
              std::max(exhaustive.mi_brake_selected, exhaustive.mi_accelerate_selected), 0.02);
}

TEST(planner, work_counts_are_zero_without_relevant_obstacles_and_grow_with_interaction) {
  plan_input far = ego_only(12.0);
  far.obstacles.push_back(vehicle(7, {{300.0, 0.0}, pi}, 15.0, 0.0, far.time));
  const plan_work none = plan(far).work;
  EXPECT_EQ(none.relevant_obstacles, 0u);
  EXPECT_EQ(none.bound_checks + none.distance_evaluations + none.refinements + none.translation_minima +
                none.assignments_evaluated,
            0u);

  const plan_input in = crossing_scene();
  const plan_work one = plan(in).work;
  EXPECT_EQ(one.relevant_obstacles, 1u);
  EXPECT_GT(one.bound_checks, 0u);
  EXPECT_GT(one.distance_evaluations + one.translation_minima, 0u);
  EXPECT_GT(one.refinements + one.translation_minima, 0u)
      << "the boundary crosses cells, whose corners' minima are refined or found in closed form";
  // Deterministic, and never more distances than bound checks could have let through.
  const plan_work again = plan(in).work;
  EXPECT_EQ(again.bound_checks, one.bound_checks);
  EXPECT_EQ(again.distance_evaluations, one.distance_evaluations);
  EXPECT_EQ(again.refinements, one.refinements);
  EXPECT_EQ(again.translation_minima, one.translation_minima);
  EXPECT_LE(one.distance_evaluations, one.bound_checks);
  // The reference path computes everything and reports no fast-path work.
  EXPECT_EQ(plan_reference(in).work.bound_checks, 0u);
}

/// `in` mirrored about the x-axis: y ↦ −y, headings and curvatures change sign.
plan_input mirrored(plan_input in) {
  const auto flip = [](pose& p) {
    p.position.y = -p.position.y;
    p.heading = -p.heading;
  };
  flip(in.ego.pose);
  in.nominal.curvature = -in.nominal.curvature;
  for (obstacle_track& o : in.obstacles) {
    for (observation& h : o.history) flip(h.pose);
    if (auto* polygon = std::get_if<convex_polygon>(&o.shape)) {
      for (vec2& v : polygon->vertices) v.y = -v.y;
    }
  }
  return in;
}

/// `in` rotated by `angle` about the origin, then moved by `shift`.
plan_input moved(plan_input in, double angle, vec2 shift) {
  const auto move = [&](pose& p) {
    p.position = rotated(p.position, std::cos(angle), std::sin(angle)) + shift;
    p.heading += angle;
  };
  move(in.ego.pose);
  for (obstacle_track& o : in.obstacles) {
    for (observation& h : o.history) move(h.pose);
  }
  return in;
}

void expect_same_indices(const plan_result& a, const plan_result& b, const std::string& context) {
  ASSERT_TRUE(a.ok() && b.ok()) << a.error << b.error;
  for (std::size_t i = 0; i < a.forecast_times.size(); ++i) {
    EXPECT_NEAR(a.mi_brake[i], b.mi_brake[i], 1e-9) << context << " tau index " << i;
    EXPECT_NEAR(a.mi_accelerate[i], b.mi_accelerate[i], 1e-9) << context << " tau index " << i;
    EXPECT_EQ(a.excluded[i], b.excluded[i]) << context;
  }
  EXPECT_EQ(a.forecast_index, b.forecast_index) << context;
  EXPECT_EQ(a.selected_family, b.selected_family) << context;
  EXPECT_EQ(a.mode, b.mode) << context;
}

TEST(planner, mirroring_the_scene_mirrors_the_curvature_and_keeps_the_indices) {
  std::mt19937_64 rng(101);
  for (int trial = 0; trial < 20; ++trial) {
    const plan_input in = trial == 0 ? crossing_scene() : testing::random_scene(rng);
    const plan_result a = plan(in);
    const plan_result b = plan(mirrored(in));
    expect_same_indices(a, b, testing::describe(in));
    EXPECT_NEAR(a.command.acceleration, b.command.acceleration, 1e-9) << testing::describe(in);
    EXPECT_NEAR(a.command.curvature, -b.command.curvature, 1e-9) << testing::describe(in);
  }
}

TEST(planner, moving_the_whole_scene_changes_nothing) {
  std::mt19937_64 rng(202);
  for (int trial = 0; trial < 20; ++trial) {
    const plan_input in = trial == 0 ? crossing_scene() : testing::random_scene(rng);
    const plan_result a = plan(in);
    const plan_result b = plan(moved(in, 2.1, {-130.0, 47.5}));
    expect_same_indices(a, b, testing::describe(in));
    EXPECT_NEAR(a.command.acceleration, b.command.acceleration, 1e-9);
    EXPECT_NEAR(a.command.curvature, b.command.curvature, 1e-9);
  }
}

TEST(planner, a_larger_safety_margin_never_increases_an_index) {
  std::mt19937_64 rng(303);
  for (int trial = 0; trial < 20; ++trial) {
    plan_input in = trial == 0 ? crossing_scene() : testing::random_scene(rng);
    std::vector<plan_result> results;
    for (const double margin : {0.0, 0.3, 1.0}) {
      in.config.safety_margin = margin;
      results.push_back(plan(in));
      ASSERT_TRUE(results.back().ok());
    }
    for (std::size_t k = 1; k < results.size(); ++k) {
      for (std::size_t i = 0; i < results[k].forecast_times.size(); ++i) {
        EXPECT_LE(results[k].mi_brake[i], results[k - 1].mi_brake[i]) << testing::describe(in);
        EXPECT_LE(results[k].mi_accelerate[i], results[k - 1].mi_accelerate[i]) << testing::describe(in);
      }
      EXPECT_LE(results[k].time_to_collision, results[k - 1].time_to_collision);
    }
  }
}

TEST(planner, a_stopped_ego_beside_crossing_traffic_stays_put) {
  plan_input in = ego_only(0.0);
  in.nominal = {3.0, 0.0};  // it would like to pull out at full throttle
  // A car crossing 4.9 m ahead, from the right, at 12 m/s: in the ego's way from 0.74 s to 1.26 s.
  in.obstacles.push_back(vehicle(1, {{4.9, -12.0}, pi / 2.0}, 12.0, 0.0, in.time));
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  // AS− of a stopped ego is the single displacement "stay": safe, so MI− = 1.
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) EXPECT_EQ(r.mi_brake[i], 1.0);
  EXPECT_LT(r.mi_accelerate[0], 1.0);
  EXPECT_EQ(r.selected_family, family::brake);
  EXPECT_EQ(r.mode, planning_mode::avoid);
  EXPECT_LE(r.command.acceleration, 0.0);
}

TEST(planner, a_vehicle_standing_in_the_lane_is_avoided_and_late_forecasts_are_excluded) {
  plan_input in = ego_only(10.0);
  obstacle_track parked;
  parked.id = 4;
  parked.kind = obstacle_kind::static_obstacle;
  parked.history = {{in.time, {{20.0, 0.0}, 0.0}, 0.0}};
  in.obstacles.push_back(parked);
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  // Rear of the parked car at 17.75 m, ego front at 2.25 m: TTC = 15.5 m / 10 m/s.
  EXPECT_NEAR(r.time_to_collision, 1.55, 1e-3);
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    EXPECT_EQ(r.excluded[i], r.forecast_times[i] > 1.55 ? 1 : 0) << i;
    // A standing obstacle is forecast the same whatever τ.
    EXPECT_EQ(r.mi_brake[i], r.mi_brake[0]);
    EXPECT_EQ(r.mi_accelerate[i], r.mi_accelerate[0]);
  }
  EXPECT_EQ(r.forecast_time, 0.0) << "ties go to the smallest forecast time";
  // Braking to a stop short of it (from 10 m/s at up to 7 m/s²) and steering around it both work:
  // both families keep most of their room, and nearly as much as each other.
  EXPECT_GT(r.mi_brake[0], 0.6);
  EXPECT_GT(r.mi_accelerate[0], 0.6);
  EXPECT_LT(std::max(r.mi_brake[0], r.mi_accelerate[0]), 0.9);
  EXPECT_EQ(r.mode, planning_mode::avoid);
  const forecast_obstacle car{r.obstacles[0].motion, rectangle{}};
  EXPECT_FALSE(maneuver_collides(in.ego, r.command, std::span(&car, 1), std::vector<double>{0.0}, {1.0, 3.0, 0.001, 0.0}));
}

TEST(planner, a_pedestrian_crossing_ahead_makes_the_ego_yield) {
  plan_input in = ego_only(40.0 / 3.6);
  obstacle_track walker;
  walker.id = 9;
  walker.kind = obstacle_kind::pedestrian;
  walker.shape = disc{0.35};
  // Crossing from the right at 1.4 m/s, reaching the ego's lane centre when the ego's front does.
  const double meet = 1.6;
  const double x = 40.0 / 3.6 * meet + 2.25;
  walker.history = testing::ctrv_history({{x, -1.4 * meet}, pi / 2.0}, 1.4, 0.0, in.time);
  in.obstacles.push_back(walker);
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_NEAR(r.time_to_collision, meet, 0.35);
  EXPECT_NE(r.mode, planning_mode::nominal);
  EXPECT_GT(r.mi_brake_selected, 0.5) << "braking before the walker's path is easy from 40 km/h";
  const forecast_obstacle w{r.obstacles[0].motion, disc{0.35}};
  EXPECT_FALSE(maneuver_collides(in.ego, r.command, std::span(&w, 1), std::vector<double>{r.forecast_time},
                                 {1.0, 3.0, 0.001, 0.0}));
}

TEST(planner, an_input_that_needs_a_time_step_below_the_floor_is_refused_and_one_just_above_is_planned) {
  // A footprint of micrometres: the tunneling bound is far below 0.1 ms.
  plan_input tiny = crossing_scene();
  tiny.obstacles[0].shape = disc{1e-6};
  const plan_result refused = plan(tiny);
  EXPECT_EQ(refused.status, plan_status::invalid_input);
  EXPECT_NE(refused.error.find("obstacles[0] (id 1): the collision time step the tunneling bound of spec §5"),
            std::string::npos)
      << refused.error;
  EXPECT_EQ(plan_reference(tiny).status, plan_status::invalid_input);
  // A speed no road user has (the fuzzer's recorded 4.4e27 m/s made the sample count overflow).
  plan_input fast = crossing_scene();
  fast.ego.limits.speed_cap = 4.4e27;
  fast.ego.speed = 4.4e27;
  EXPECT_EQ(plan(fast).status, plan_status::invalid_input);
  // A step above the floor that would sample more pairs than a step may hold: a fine resolution
  // over a long window with a small walker (the pairs at max_time_step alone are within the bound).
  plan_input crowded = crossing_scene();
  crowded.config.resolution = {101, 101};
  crowded.config.collision_window = 30.0;
  crowded.obstacles[0].shape = disc{0.01};
  ASSERT_FALSE(validation_error(crowded)) << *validation_error(crowded);
  const plan_result too_many = plan(crowded);
  EXPECT_EQ(too_many.status, plan_status::invalid_input);
  EXPECT_NE(too_many.error.find("config.collision_window = 30 s at the collision time step of"), std::string::npos)
      << too_many.error;
  EXPECT_NE(too_many.error.find("exceed the 5e8 pairs"), std::string::npos) << too_many.error;
  // A disc whose tunneling bound is just above the floor is planned on.
  const double speeds = 40.0 / 3.6 + 3.0 * 1.0 + 10.0;  // the ego's top speed within T_h, and the car's
  plan_input small = crossing_scene();
  small.obstacles[0].shape = disc{1.01 * smallest_collision_time_step * speeds / 2.0};
  const plan_result planned = plan(small);
  ASSERT_TRUE(planned.ok()) << planned.error;
  EXPECT_GE(planned.collision_time_step, smallest_collision_time_step);
}

TEST(planner, a_kept_planner_plans_another_grid_of_as_many_samples_as_plan_does) {
  // 4 × 5 and 6 × 3 accelerations × curvatures both make 24 samples per family with the
  // nominal-curvature column: at the same speed a kept planner once took the second grid for the
  // first and kept its placements (found by the planner's fuzzer, 2026-12-07).
  std::mt19937_64 rng(5);
  std::size_t differ = 0;
  for (int trial = 0; trial < 20; ++trial) {
    plan_input in = testing::random_scene(rng, {1 + static_cast<std::size_t>(trial % 3), trial % 2 == 1});
    planner kept;
    in.config.resolution = trial % 2 == 0 ? sampling_resolution{4, 5} : sampling_resolution{6, 3};
    const plan_result first = kept.plan(in);
    in.config.resolution = trial % 2 == 0 ? sampling_resolution{6, 3} : sampling_resolution{4, 5};
    const plan_result fresh = plan(in);
    const plan_result again = kept.plan(in);
    ASSERT_TRUE(fresh.ok() && again.ok()) << fresh.error;
    EXPECT_EQ(again.command, fresh.command) << "trial " << trial;
    EXPECT_EQ(again.mi_brake, fresh.mi_brake) << "trial " << trial;
    EXPECT_EQ(again.mi_accelerate, fresh.mi_accelerate) << "trial " << trial;
    differ += first.mi_brake != fresh.mi_brake || first.mi_accelerate != fresh.mi_accelerate ? 1 : 0;
  }
  EXPECT_GT(differ, 5U) << "the two grids must give other maps often for this test to mean anything";
}

TEST(planner, a_command_outside_the_limits_is_clamped) {
  plan_input in = ego_only(10.0);
  in.nominal = {12.0, 0.5};
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.command, (maneuver{3.0, 0.05}));
}

TEST(planner, constant_policy_uses_its_forecast_time_unless_it_exceeds_the_time_to_collision) {
  plan_input in = crossing_scene();
  in.config.policy = {forecast_policy_kind::constant, 1.0};
  plan_result r = plan(in);
  ASSERT_TRUE(r.ok());
  ASSERT_GT(r.time_to_collision, 1.0);
  EXPECT_EQ(r.forecast_time, 1.0);
  in.config.policy = {forecast_policy_kind::constant, 2.0};
  r = plan(in);
  ASSERT_LT(r.time_to_collision, 2.0);
  EXPECT_LE(r.forecast_time, r.time_to_collision);
  EXPECT_GT(r.forecast_time, r.time_to_collision - 0.125);
}

/// The ego at 40 km/h and a car 20 m ahead, `lateral` m to its side, heading north-west at 9 m/s
/// and turning at `yaw_rate`: its forecasts differ from one forecast time to the next.
plan_input turning_car_ahead(double lateral, double yaw_rate, forecast_policy_kind policy) {
  plan_input in = ego_only(40.0 / 3.6);
  const pose at{{20.0, lateral}, 0.75 * pi};
  obstacle_track track;
  track.id = 1;
  track.history = {{in.time, at, 9.0}};
  track.motion = motion_estimate{at, 9.0, yaw_rate};
  in.obstacles.push_back(track);
  in.config.policy.kind = policy;
  return in;
}

/// True when `u` is proven collision-free with the one obstacle of `r` under forecast time τ_i.
bool free_under(const plan_input& in, const plan_result& r, const maneuver& u, std::size_t i) {
  const std::array<forecast_obstacle, 1> obstacle{forecast_obstacle{r.obstacles[0].motion, in.obstacles[0].shape}};
  const std::array<double, 1> tau{r.forecast_times[i]};
  const collision_window window{in.config.displacement_horizon, in.config.collision_window, r.collision_time_step,
                                in.config.safety_margin};
  return verified_collision_free_reference(in.ego, u, obstacle, tau, window);
}

TEST(planner, the_robust_policy_avoids_what_a_turn_forecast_by_any_non_excluded_forecast_time_would_hit) {
  // ADJ trusts the straight-line forecast (τ̄ = 0), under which going straight is safe; the robust
  // policy leaves it, for a maneuver safe under every forecast time up to TTC.
  const plan_input adj_in = turning_car_ahead(-3.0, 0.3, forecast_policy_kind::adjustable);
  const plan_result adj = plan(adj_in);
  ASSERT_TRUE(adj.ok()) << adj.error;
  EXPECT_EQ(adj.mode, planning_mode::nominal);
  EXPECT_FALSE(adj.robust);
  const plan_input in = turning_car_ahead(-3.0, 0.3, forecast_policy_kind::robust);
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_TRUE(r.robust);
  EXPECT_EQ(r.mode, planning_mode::avoid);
  EXPECT_NE(r.command, adj.command);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    if (r.excluded[i] != 0) continue;
    EXPECT_TRUE(free_under(in, r, r.command, i)) << "tau " << r.forecast_times[i];
    // The robust sets lie inside every non-excluded forecast time's.
    EXPECT_LE(r.mi_brake_selected, r.mi_brake[i] + 1e-12) << "tau " << r.forecast_times[i];
    EXPECT_LE(r.mi_accelerate_selected, r.mi_accelerate[i] + 1e-12) << "tau " << r.forecast_times[i];
    ++checked;
  }
  EXPECT_GT(checked, 4u);
  EXPECT_FALSE(free_under(in, r, in.nominal, r.forecast_index)) << "going straight hits the turning car";
  // τ̄ reports the largest forecast time the command is safe under: the last one not excluded.
  EXPECT_EQ(r.excluded[r.forecast_index], 0);
  ASSERT_LT(r.forecast_index + 1, r.forecast_times.size());
  EXPECT_NE(r.excluded[r.forecast_index + 1], 0);
}

TEST(planner, the_robust_policy_s_safe_samples_are_those_safe_under_every_non_excluded_forecast_time) {
  for (const bool reference : {false, true}) {
    plan_input in = turning_car_ahead(-3.0, 0.3, forecast_policy_kind::robust);
    in.config.record_samples = true;
    in.config.resolution = {11, 15};
    const plan_result r = reference ? plan_reference(in, {{11, 15}}) : plan(in);
    ASSERT_TRUE(r.ok() && r.samples) << r.error;
    ASSERT_TRUE(r.robust);
    const sample_snapshot& s = *r.samples;
    std::size_t safe = 0;
    std::size_t unsafe_under_some = 0;
    for (std::size_t m = 0; m < s.maneuvers.size(); ++m) {
      bool under_every = true;
      bool under_some = false;
      for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
        if (r.excluded[i] != 0) continue;
        under_every = under_every && s.safe_by_forecast[i][m] != 0;
        under_some = under_some || s.safe_by_forecast[i][m] != 0;
      }
      EXPECT_EQ(s.safe_selected[m] != 0, under_every) << (reference ? "reference" : "fast") << ", sample " << m;
      safe += under_every ? 1 : 0;
      unsafe_under_some += under_some && !under_every ? 1 : 0;
    }
    EXPECT_GT(safe, 0u);
    EXPECT_GT(unsafe_under_some, 10u) << "the forecast times must disagree for this test to mean anything";
  }
}

TEST(planner, the_robust_policy_falls_back_to_adj_when_no_maneuver_is_safe_under_every_forecast_time) {
  const plan_result adj = plan(turning_car_ahead(-6.0, 0.6, forecast_policy_kind::adjustable));
  const plan_result r = plan(turning_car_ahead(-6.0, 0.6, forecast_policy_kind::robust));
  ASSERT_TRUE(r.ok() && adj.ok());
  EXPECT_FALSE(r.robust);
  EXPECT_EQ(r.mode, planning_mode::avoid) << "ADJ still finds room under one forecast time";
  EXPECT_EQ(r.command, adj.command);
  EXPECT_EQ(r.mode, adj.mode);
  EXPECT_EQ(r.forecast_index, adj.forecast_index);
  EXPECT_EQ(r.mi_brake_selected, adj.mi_brake_selected);
  EXPECT_EQ(r.mi_accelerate_selected, adj.mi_accelerate_selected);
  EXPECT_EQ(r.mi_brake, adj.mi_brake);
}

TEST(planner, the_robust_policy_decides_as_adj_against_an_obstacle_that_does_not_turn) {
  // Every forecast time gives the same forecast: the robust sets are ADJ's, only τ̄ differs.
  const plan_result adj = plan(turning_car_ahead(-3.0, 0.0, forecast_policy_kind::adjustable));
  const plan_result r = plan(turning_car_ahead(-3.0, 0.0, forecast_policy_kind::robust));
  ASSERT_TRUE(r.ok() && adj.ok());
  ASSERT_TRUE(r.robust);
  EXPECT_EQ(r.command, adj.command);
  EXPECT_EQ(r.mode, adj.mode);
  EXPECT_EQ(r.selected_family, adj.selected_family);
  EXPECT_EQ(r.mi_brake_selected, adj.mi_brake_selected);
  EXPECT_EQ(r.mi_accelerate_selected, adj.mi_accelerate_selected);
  // Without obstacles the nominal maneuver is safe under every forecast time, 0 to 2 s.
  plan_input alone = ego_only(10.0);
  alone.config.policy.kind = forecast_policy_kind::robust;
  const plan_result free = plan(alone);
  EXPECT_TRUE(free.robust);
  EXPECT_EQ(free.mode, planning_mode::nominal);
  EXPECT_EQ(free.forecast_time, 2.0);
}

TEST(planner, recorded_samples_describe_the_sets_the_reference_indices_were_computed_from) {
  plan_input in = crossing_scene();
  in.config.record_samples = true;
  const plan_result r = plan_reference(in, {{11, 15}});
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r.samples);
  const sample_snapshot& s = *r.samples;
  ASSERT_EQ(s.safe_by_forecast.size(), r.forecast_times.size());
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    double total[2] = {0.0, 0.0};
    double safe[2] = {0.0, 0.0};
    for (std::size_t m = 0; m < s.maneuvers.size(); ++m) {
      const int f = s.families[m] == family::brake ? 0 : 1;
      total[f] += s.area_weights[m];
      if (s.safe_by_forecast[i][m]) safe[f] += s.area_weights[m];
    }
    EXPECT_NEAR(safe[0] / total[0], r.mi_brake[i], 1e-12);
    EXPECT_NEAR(safe[1] / total[1], r.mi_accelerate[i], 1e-12);
  }
  // End points are the displacements in the world frame: the straight full-throttle one.
  bool found = false;
  for (std::size_t m = 0; m < s.maneuvers.size(); ++m) {
    if (s.maneuvers[m] == maneuver{3.0, 0.0} && !s.on_nominal_curvature[m]) {
      EXPECT_NEAR(s.end_points[m].x, 40.0 / 3.6 + 1.5, 1e-9);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(planner, recorded_samples_of_the_fast_planner_are_those_of_the_reference_at_the_same_resolution) {
  plan_input in = crossing_scene();
  in.config.record_samples = true;
  in.config.resolution = {11, 15};
  in.config.max_time_step = 0.02;
  const plan_result fast = plan(in);
  const plan_result reference = plan_reference(in, {{11, 15}});
  ASSERT_TRUE(fast.samples && reference.samples);
  // A sample the fast planner finds colliding really overlaps at some time, so the reference (exact
  // in continuous time) finds it colliding too. The reverse can fail only for a contact the fast
  // planner's time sampling misses entirely, which must be rare.
  std::size_t missed = 0;
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
    for (std::size_t m = 0; m < fast.samples->maneuvers.size(); ++m) {
      if (!fast.samples->safe_by_forecast[i][m]) {
        EXPECT_FALSE(reference.samples->safe_by_forecast[i][m]) << "tau index " << i << " sample " << m;
      }
      colliding += reference.samples->safe_by_forecast[i][m] ? 0 : 1;
      missed += !reference.samples->safe_by_forecast[i][m] && fast.samples->safe_by_forecast[i][m] ? 1 : 0;
    }
  }
  EXPECT_GT(colliding, 100u);
  EXPECT_LE(missed, colliding / 100);
  EXPECT_EQ(fast.samples->maneuvers, reference.samples->maneuvers);
  EXPECT_EQ(fast.samples->area_weights, reference.samples->area_weights);
  // The fast indices interpolate between the samples; the reference counts them.
  for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
    EXPECT_NEAR(fast.mi_brake[i], reference.mi_brake[i], 0.06);
    EXPECT_NEAR(fast.mi_accelerate[i], reference.mi_accelerate[i], 0.06);
  }
}

TEST(planner, inside_the_margin_the_near_crash_brakes_hardest_and_steers_away_from_the_body) {
  // A stopped car 0.2 m to the right of the ego (the margin is 0.3 m), and a path that turns right
  // into it: every maneuver collides at t = 0, and braking hardest along the nominal curvature would
  // touch the car, which braking as hard and steering left does not (docs/method.md §5 item 6).
  plan_input in = ego_only(5.7);
  in.config.safety_margin = 0.3;
  in.nominal = {-7.0, -0.15};
  in.obstacles.push_back(vehicle(5, {{4.0, -2.0}, 0.0}, 0.0, 0.0, in.time));
  const collision_window bodies{in.config.displacement_horizon, in.config.collision_window,
                                in.config.max_time_step, 0.0};
  const std::array<forecast_obstacle, 1> car{forecast_obstacle{{{{4.0, -2.0}, 0.0}, 0.0, 0.0}, rectangle{}}};
  const std::array<double, 1> tau{0.0};
  ASSERT_NE(first_collision_time(in.ego, in.nominal, car, tau, bodies), no_collision);  // the premise
  for (const bool reference : {false, true}) {
    const plan_result r = reference ? plan_reference(in) : plan(in);
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.mode, planning_mode::near_crash) << reference;
    EXPECT_EQ(r.command.acceleration, -in.ego.limits.max_deceleration) << reference;
    EXPECT_GT(r.command.curvature, in.nominal.curvature) << reference;
    EXPECT_EQ(first_collision_time(in.ego, r.command, car, tau, bodies), no_collision)
        << reference << ": " << r.command.acceleration << ", " << r.command.curvature;
  }
}

TEST(planner, a_car_driving_alongside_just_outside_the_margin_leaves_the_nominal_maneuver_proven_safe) {
  // A car at the ego's speed on its left, 5 mm outside the 0.3 m margin: every maneuver starts 5 mm
  // from the margin, where the proof's speed bound steps 5 mm / L, below its resolution, and proves
  // nothing; the translation bound proves the nominal maneuver, which keeps the 5 mm, and the step
  // is not a near-crash (docs/method.md §4.5).
  plan_input in = ego_only(10.0);
  in.config.safety_margin = 0.3;
  const double beside = 0.9 + 0.9 + 0.3 + 0.005;
  in.obstacles.push_back(vehicle(7, {{0.0, beside}, 0.0}, 10.0, 0.0, in.time));
  const collision_window window{in.config.displacement_horizon, in.config.collision_window, in.config.max_time_step,
                                in.config.safety_margin};
  const std::array<forecast_obstacle, 1> car{forecast_obstacle{{{{0.0, beside}, 0.0}, 10.0, 0.0}, rectangle{}}};
  const std::array<double, 1> tau{0.0};
  ASSERT_FALSE(verified_collision_free(in.ego, in.nominal, car, tau, window, command_proof_resolution,
                                       proof_steps::speed_bound));  // the premise
  // The reference on a coarser grid than its own: its proofs of this scene's dense grid take seconds.
  const reference_resolution coarse{{11, 15}};
  for (const bool reference : {false, true}) {
    const plan_result r = reference ? plan_reference(in, coarse) : plan(in);
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.mode, planning_mode::nominal) << reference;
    EXPECT_EQ(r.command, in.nominal) << reference;
  }
}

TEST(planner, rule_1_accepts_u_nom_proven_with_each_obstacle_alone_so_deciding_only_the_command_decides_the_same) {
  // A car crossing 20 m ahead, and a car alongside 0.4 m away: the proof of u_nom with both at once
  // fails, and the proof with each alone succeeds (found by scanning the crossing car's start; the
  // assertions below keep the scene honest). The full step must accept that, as the shortcut of
  // `decision_only` does.
  plan_input in = ego_only(10.0);
  const auto given = [&](std::uint32_t id, pose at) {
    obstacle_track track;
    track.id = id;
    track.history = {{in.time, at, 10.0}};
    track.motion = motion_estimate{at, 10.0, 0.0};
    return track;
  };
  in.obstacles.push_back(given(1, {{20.0, -20.0 - 6.3278}, pi / 2.0}));
  in.obstacles.push_back(given(2, {{0.0, 2.2}, 0.0}));
  in.config.map_column = false;
  std::vector<forecast_obstacle> both;
  for (const obstacle_track& t : in.obstacles) both.push_back({*t.motion, t.shape});
  const std::array<double, 2> tau{0.0, 0.0};
  const collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05,
                                in.config.safety_margin};
  ASSERT_FALSE(verified_collision_free(in.ego, in.nominal, both, tau, window)) << "the scene no longer has its property";
  ASSERT_TRUE(verified_collision_free(in.ego, in.nominal, std::span(both).first(1), std::span(tau).first(1), window));
  ASSERT_TRUE(verified_collision_free(in.ego, in.nominal, std::span(both).last(1), std::span(tau).last(1), window));

  const plan_result full = plan(in);
  in.config.decision_only = true;
  const plan_result lean = plan(in);
  ASSERT_TRUE(full.ok() && lean.ok());
  EXPECT_FALSE(lean.indices_computed);
  EXPECT_EQ(full.mode, planning_mode::nominal);
  EXPECT_EQ(full.command, in.nominal);
  EXPECT_EQ(lean.command, full.command);
}

}  // namespace
}  // namespace mm
