#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "mm/collision.hpp"
#include "mm/footprint.hpp"
#include "mm/planner.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

plan_input valid_input() {
  plan_input in;
  in.time = 2.0;
  in.ego.speed = 10.0;
  obstacle_track b;
  b.id = 5;
  b.history = testing::ctrv_history({{20.0, 10.0}, -1.5}, 8.0, 0.1, in.time);
  in.obstacles.push_back(b);
  return in;
}

/// `mutate` makes the input invalid; the error must name `field` and say `what`.
template <class Mutate>
void expect_rejected(Mutate mutate, const std::string& field, const std::string& what) {
  plan_input in = valid_input();
  mutate(in);
  const plan_result r = plan(in);
  EXPECT_EQ(r.status, plan_status::invalid_input) << field;
  EXPECT_NE(r.error.find(field), std::string::npos) << "error: " << r.error << "\nexpected field: " << field;
  EXPECT_NE(r.error.find(what), std::string::npos) << "error: " << r.error << "\nexpected: " << what;
  EXPECT_EQ(validation_error(in).value_or(""), r.error);
}

TEST(validation, the_valid_input_is_accepted) {
  EXPECT_FALSE(validation_error(valid_input()));
  EXPECT_TRUE(plan(valid_input()).ok());
}

TEST(validation, non_finite_ego_state_is_rejected_by_field) {
  expect_rejected([](plan_input& in) { in.ego.pose.position.x = nan; }, "ego.pose.position.x", "finite");
  expect_rejected([](plan_input& in) { in.ego.pose.heading = inf; }, "ego.pose.heading", "finite");
  expect_rejected([](plan_input& in) { in.ego.speed = nan; }, "ego.speed", "NaN");
  expect_rejected([](plan_input& in) { in.ego.speed = -1.0; }, "ego.speed", "≥ 0");
  expect_rejected([](plan_input& in) { in.ego.speed = 31.0; }, "ego.speed", "speed_cap");
  expect_rejected([](plan_input& in) { in.nominal.curvature = nan; }, "nominal.curvature", "finite");
  expect_rejected([](plan_input& in) { in.time = inf; }, "time", "finite");
}

TEST(validation, non_positive_dimensions_and_limits_are_rejected) {
  expect_rejected([](plan_input& in) { in.ego.shape = rectangle{0.0, 1.8}; }, "ego.shape", "length");
  expect_rejected([](plan_input& in) { in.obstacles[0].shape = disc{-0.3}; }, "obstacles[0] (id 5).shape", "radius");
  expect_rejected([](plan_input& in) { in.ego.limits.max_deceleration = -7.0; }, "ego.limits.max_deceleration",
                  "positive");
  expect_rejected([](plan_input& in) { in.ego.limits.max_acceleration = 0.0; }, "ego.limits.max_acceleration",
                  "positive");
  expect_rejected([](plan_input& in) { in.ego.limits.min_turning_radius = nan; }, "ego.limits.min_turning_radius",
                  "finite");
  expect_rejected([](plan_input& in) { in.ego.limits.speed_cap = 0.0; }, "ego.limits.speed_cap", "positive");
  expect_rejected([](plan_input& in) { in.config.safety_margin = -0.1; }, "config.safety_margin", "from 0");
  expect_rejected([](plan_input& in) { in.config.resolution.accelerations = 1; }, "config.resolution.accelerations",
                  "from 2");
}

TEST(validation, magnitudes_beyond_any_road_user_are_rejected_with_the_bound) {
  // Positive and finite, but so large (or a turning radius so small) that squares and products of
  // them overflow: found by the planner's fuzzer (a turning radius of 5e-324 m gave NaN indices).
  expect_rejected([](plan_input& in) { in.ego.limits.min_turning_radius = 5e-324; }, "ego.limits.min_turning_radius",
                  "at least 0.001");
  expect_rejected([](plan_input& in) { in.ego.limits.speed_cap = 1e6; }, "ego.limits.speed_cap", "up to 1000");
  expect_rejected([](plan_input& in) { in.ego.limits.max_acceleration = 1e300; }, "ego.limits.max_acceleration",
                  "up to 1000");
  expect_rejected([](plan_input& in) { in.ego.limits.max_lateral_acceleration = 2e3; },
                  "ego.limits.max_lateral_acceleration", "up to 1000");
  expect_rejected([](plan_input& in) { in.ego.pose.position.y = -2e8; }, "ego.pose.position.y", "within ±1e+08 m");
  expect_rejected([](plan_input& in) { in.ego.shape = rectangle{1e301, 1.8}; }, "ego.shape",
                  "rectangle length must be a positive number of metres up to 1000, got 1e+301");
  expect_rejected([](plan_input& in) { in.obstacles[0].shape = convex_polygon{{{0.0, 0.0}, {2e3, 0.0}, {0.0, 1.0}}}; },
                  "obstacles[0] (id 5).shape", "more than 1000 m from the reference point");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[2].pose.position.x = 2e8; },
                  "obstacles[0] (id 5).history[2].pose.position.x", "within ±1e+08 m");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[3].speed = -1e20; },
                  "obstacles[0] (id 5).history[3].speed", "within ±1000 m/s");
  expect_rejected(
      [](plan_input& in) { in.obstacles[0].motion = motion_estimate{in.obstacles[0].history.back().pose, 5e3, 0.0}; },
      "obstacles[0] (id 5).motion.speed", "within ±1000 m/s");
  expect_rejected([](plan_input& in) { in.config.safety_margin = 1e4; }, "config.safety_margin", "from 0 to 1000");
  expect_rejected(
      [](plan_input& in) { in.obstacles[0].motion = motion_estimate{in.obstacles[0].history.back().pose, 5.0, 1e308}; },
      "obstacles[0] (id 5).motion.yaw_rate", "within ±100 rad/s");
  expect_rejected([](plan_input& in) { in.time = 1e300; }, "obstacles[0] (id 5).history.back().time",
                  "no more than 1000 s before the planning time 1e+300 s");
}

TEST(validation, inputs_at_the_bounds_are_planned_to_finite_results) {
  // The largest and smallest accepted magnitudes together are planned, every result finite.
  plan_input in = valid_input();
  in.ego.pose.position = {largest_input_coordinate - 5e3, -largest_input_coordinate + 5e3};  // the obstacle's track within the bound
  in.ego.limits = {largest_input_acceleration, largest_input_acceleration, largest_input_acceleration,
                   smallest_input_turning_radius, largest_input_speed, true};
  in.ego.shape = rectangle{largest_footprint_size, largest_footprint_size};
  in.config.safety_margin = largest_input_safety_margin;
  in.config.resolution = {3, 3};
  in.obstacles[0].history = testing::ctrv_history({in.ego.pose.position + vec2{-2e3, 0.0}, 0.3}, 900.0, 0.1, in.time);
  in.obstacles[0].shape = disc{largest_footprint_size};
  for (const double speed : {0.0, 1e-300, 5.0, largest_input_speed}) {
    in.ego.speed = speed;
    const plan_result r = plan(in);
    EXPECT_EQ(validation_error(in), std::nullopt) << speed;
    ASSERT_TRUE(r.ok()) << speed << ": " << r.error;
    EXPECT_TRUE(std::isfinite(r.command.acceleration) && std::isfinite(r.command.curvature)) << speed;
    EXPECT_TRUE(r.mi_brake_selected >= 0.0 && r.mi_brake_selected <= 1.0) << speed;
    EXPECT_TRUE(r.mi_accelerate_selected >= 0.0 && r.mi_accelerate_selected <= 1.0) << speed;
    for (std::size_t i = 0; i < r.mi_brake.size(); ++i) {
      EXPECT_TRUE(r.mi_brake[i] >= 0.0 && r.mi_brake[i] <= 1.0) << speed << " " << i;
      EXPECT_TRUE(r.mi_accelerate[i] >= 0.0 && r.mi_accelerate[i] <= 1.0) << speed << " " << i;
    }
  }
}

TEST(validation, an_empty_forecast_grid_or_one_beyond_the_collision_window_is_rejected) {
  expect_rejected([](plan_input& in) { in.config.forecast_count = 0; }, "config.forecast_count", "empty");
  expect_rejected([](plan_input& in) { in.config.collision_window = 1.5; }, "config.forecast_count",
                  "exceeds config.collision_window");
  expect_rejected([](plan_input& in) { in.config.forecast_step = 0.0; }, "config.forecast_step", "positive");
  expect_rejected([](plan_input& in) { in.config.collision_window = 0.5; }, "config.collision_window",
                  "at least config.displacement_horizon");
  expect_rejected(
      [](plan_input& in) { in.config.policy = {forecast_policy_kind::constant, 0.3}; },
      "config.policy.constant_forecast_time", "on the grid");
  expect_rejected(
      [](plan_input& in) { in.config.policy = {forecast_policy_kind::constant, 2.5}; },
      "config.policy.constant_forecast_time", "on the grid");
}

TEST(validation, a_planning_step_too_large_to_hold_is_rejected_before_anything_is_sampled) {
  // Found by hand on 2026-12-05: a window of 1e9 s ran out of memory (std::bad_alloc) and a step of
  // 1e-9 s did not finish within a minute; the forecast grid and the steps are now bounded as the resolution is.
  expect_rejected([](plan_input& in) { in.config.max_time_step = 1e-9; }, "config.max_time_step",
                  "at least 0.0001 s");
  expect_rejected([](plan_input& in) { in.config.collision_window = 1e9; }, "config.collision_window",
                  "exceed the 5e8 pairs");
  expect_rejected(
      [](plan_input& in) {
        in.config.forecast_count = largest_forecast_count + 1;
        in.config.forecast_step = 0.001;
      },
      "config.forecast_count", "at most 1000");
  expect_rejected(
      [](plan_input& in) {
        in.config.resolution = {201, 201};
        in.config.collision_window = 10.0;
        in.config.max_time_step = 1e-4;
      },
      "config.collision_window", "at most 0.618 s with config.max_time_step = 1e-04 s and config.resolution 201 × 201");
  // The limits themselves are valid: the largest grid, the shortest step over the default window,
  // and the finest resolution over the default window (checked, not planned: about a minute).
  plan_input largest = valid_input();
  largest.config.forecast_count = largest_forecast_count;
  largest.config.forecast_step = 0.003;
  EXPECT_FALSE(validation_error(largest)) << *validation_error(largest);
  plan_input shortest = valid_input();
  shortest.config.max_time_step = smallest_collision_time_step;
  EXPECT_FALSE(validation_error(shortest)) << *validation_error(shortest);
  plan_input finest = valid_input();
  finest.config.resolution = {2001, 2001};
  EXPECT_FALSE(validation_error(finest)) << *validation_error(finest);
  EXPECT_LE(sampled_maneuver_count(finest.config.resolution) * sample_time_count(3.0, 0.05), largest_sample_time_pairs);
}

TEST(validation, one_observation_is_enough_when_the_caller_gives_the_motion) {
  plan_input in = valid_input();
  in.obstacles[0].history.erase(in.obstacles[0].history.begin(), in.obstacles[0].history.end() - 1);
  EXPECT_TRUE(validation_error(in).has_value());
  const observation& last = in.obstacles[0].history.back();
  in.obstacles[0].motion = motion_estimate{last.pose, last.speed, 0.1};
  EXPECT_EQ(validation_error(in), std::nullopt);
  in.obstacles[0].history.clear();
  EXPECT_TRUE(validation_error(in).has_value());
}

TEST(validation, a_history_too_short_or_out_of_order_is_rejected) {
  expect_rejected([](plan_input& in) { in.obstacles[0].history.resize(1); }, "obstacles[0] (id 5).history size",
                  "at least 2 observations");
  expect_rejected([](plan_input& in) { in.obstacles[0].history.clear(); }, "obstacles[0] (id 5).history size",
                  "at least 2");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[10].time = in.obstacles[0].history[9].time; },
                  "obstacles[0] (id 5).history[10].time", "after the previous observation");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[3].speed = nan; }, "obstacles[0] (id 5).history[3].speed",
                  "finite");
  expect_rejected([](plan_input& in) { in.time = 1.0; }, "obstacles[0] (id 5).history.back().time",
                  "no later than the planning time");
  // Every number of an observation, anywhere in the history, is named when it is not finite.
  expect_rejected([](plan_input& in) { in.obstacles[0].history[0].time = -inf; }, "obstacles[0] (id 5).history[0].time",
                  "finite");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[7].pose.position.x = inf; },
                  "obstacles[0] (id 5).history[7].pose.position.x", "finite");
  expect_rejected([](plan_input& in) { in.obstacles[0].history[12].pose.position.y = nan; },
                  "obstacles[0] (id 5).history[12].pose.position.y", "finite");
  expect_rejected([](plan_input& in) { in.obstacles[0].history.back().pose.heading = nan; },
                  "obstacles[0] (id 5).history[50].pose.heading", "finite");
  // A static obstacle needs one observation only.
  plan_input in = valid_input();
  in.obstacles[0].kind = obstacle_kind::static_obstacle;
  in.obstacles[0].history.resize(1);
  in.obstacles[0].history[0].time = in.time;
  EXPECT_TRUE(plan(in).ok());
}

TEST(validation, a_given_motion_that_is_not_finite_or_runs_backwards_is_rejected) {
  const auto with_motion = [](plan_input& in) { in.obstacles[0].motion = motion_estimate{{{20.0, 10.0}, -1.5}, 8.0, 0.1}; };
  expect_rejected([&](plan_input& in) { with_motion(in); in.obstacles[0].motion->speed = -1.0; },
                  "obstacles[0] (id 5).motion.speed", "≥ 0");
  expect_rejected([&](plan_input& in) { with_motion(in); in.obstacles[0].motion->yaw_rate = nan; },
                  "obstacles[0] (id 5).motion.yaw_rate", "finite");
  expect_rejected([&](plan_input& in) { with_motion(in); in.obstacles[0].motion->pose.position.y = inf; },
                  "obstacles[0] (id 5).motion.pose.position.y", "finite");
  plan_input in = valid_input();
  with_motion(in);
  EXPECT_TRUE(plan(in).ok());
}

TEST(validation, an_invalid_result_carries_no_command_to_act_on) {
  plan_input in = valid_input();
  in.ego.speed = nan;
  const plan_result r = plan(in);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(r.mi_brake.empty());
  EXPECT_EQ(r.command, (maneuver{0.0, 0.0}));
}

}  // namespace
}  // namespace mm
