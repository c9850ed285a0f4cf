#include "mm/forecast.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "mm/input_bounds.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

TEST(forecast, least_squares_recovers_speed_and_yaw_rate_of_exact_circular_motion) {
  obstacle_track track;
  track.history = testing::ctrv_history({{10.0, -3.0}, 2.0}, 11.1, 0.44, 5.0);
  const motion_estimate m = estimate_motion(track, 0.5, 5.0);
  EXPECT_NEAR(m.speed, 11.1, 1e-9);
  EXPECT_NEAR(m.yaw_rate, 0.44, 1e-9);
  EXPECT_NEAR(m.pose.heading, 2.0, 1e-9);
  EXPECT_NEAR(m.pose.position.x, 10.0, 1e-9);
  EXPECT_NEAR(m.pose.position.y, -3.0, 1e-9);
}

TEST(forecast, heading_estimate_survives_wrapping_through_pi) {
  obstacle_track track;
  track.history = testing::ctrv_history({{0.0, 0.0}, pi - 0.01}, 10.0, 0.5, 1.0);
  for (observation& o : track.history) o.pose.heading = wrap_angle(o.pose.heading);
  track.history.back().pose.heading = wrap_angle(pi - 0.01 + 2.0 * pi);
  const motion_estimate m = estimate_motion(track, 0.5, 1.0);
  EXPECT_NEAR(m.yaw_rate, 0.5, 1e-9);
  EXPECT_NEAR(wrap_angle(m.pose.heading - (pi - 0.01)), 0.0, 1e-9);
}

TEST(forecast, only_the_history_window_is_used) {
  // Straight at 5 m/s long ago, then turning at 0.3 rad/s for the last 0.6 s.
  obstacle_track track;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.01 * k;
    const double heading = t < 0.4 ? 0.0 : 0.3 * (t - 0.4);
    track.history.push_back({t, {{5.0 * t, 0.0}, heading}, t < 0.4 ? 5.0 : 6.0});
  }
  const motion_estimate m = estimate_motion(track, 0.5, 1.0);
  EXPECT_NEAR(m.yaw_rate, 0.3, 1e-9);
  EXPECT_NEAR(m.speed, 6.0, 1e-9);
}

TEST(forecast, the_observations_read_are_those_of_the_window_and_a_history_ending_with_them_estimates_the_same) {
  obstacle_track track;
  track.history = testing::ctrv_history({{4.0, 1.0}, 0.7}, 8.0, 0.3, 3.0, 81, 0.01);  // 0.8 s of history
  const std::size_t read = observations_read(track, 0.5);
  EXPECT_GE(read, 50U);
  EXPECT_LE(read, 51U);
  EXPECT_EQ(observations_read(track, 0.001), 2U);  // at least the last two
  const motion_estimate all = estimate_motion(track, 0.5, 3.0);
  obstacle_track cut = track;
  cut.history.erase(cut.history.begin(), cut.history.end() - static_cast<std::ptrdiff_t>(read));
  EXPECT_EQ(observations_read(cut, 0.5), read);
  const motion_estimate same = estimate_motion(cut, 0.5, 3.0);
  EXPECT_TRUE(all.pose.position == same.pose.position && all.pose.heading == same.pose.heading &&
              all.speed == same.speed && all.yaw_rate == same.yaw_rate);
  cut.history.erase(cut.history.begin());  // one fewer: one fewer read
  EXPECT_EQ(observations_read(cut, 0.5), read - 1);
  track.kind = obstacle_kind::static_obstacle;
  EXPECT_EQ(observations_read(track, 0.5), 1U);
}

TEST(forecast, noisy_observations_give_an_estimate_within_a_few_standard_errors) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> heading_noise(0.0, 0.5 * pi / 180.0);
  std::normal_distribution<double> speed_noise(0.0, 0.1);
  double worst_yaw = 0.0;
  double worst_speed = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    obstacle_track track;
    track.history = testing::ctrv_history({{0.0, 0.0}, 0.3}, 9.7, -0.2, 2.0);
    for (observation& o : track.history) {
      o.pose.heading += heading_noise(rng);
      o.speed += speed_noise(rng);
    }
    const motion_estimate m = estimate_motion(track, 0.5, 2.0);
    worst_yaw = std::max(worst_yaw, std::abs(m.yaw_rate + 0.2));
    worst_speed = std::max(worst_speed, std::abs(m.speed - 9.7));
  }
  // Standard error of the slope over 51 samples 0.01 s apart: σ/(√n·std(t)) ≈ 0.0083 rad/s;
  // of the fitted value at the window's end ≈ 0.028 m/s. Five standard errors bound 200 trials.
  EXPECT_LT(worst_yaw, 5.0 * 0.0083);
  EXPECT_LT(worst_speed, 5.0 * 0.028);
}

TEST(forecast, estimate_is_propagated_to_the_planning_time_and_clamped_to_non_negative_speed) {
  obstacle_track track;
  track.history = testing::ctrv_history({{0.0, 0.0}, 0.0}, 10.0, 0.0, 1.0);
  const motion_estimate later = estimate_motion(track, 0.5, 1.2);
  EXPECT_NEAR(later.pose.position.x, 2.0, 1e-9);
  obstacle_track creeping;
  creeping.kind = obstacle_kind::pedestrian;
  creeping.history = {{0.0, {{0.0, 0.0}, 0.0}, -0.2}, {0.1, {{0.0, 0.0}, 0.0}, -0.21}};
  EXPECT_EQ(estimate_motion(creeping, 0.5, 0.1).speed, 0.0);
}

TEST(forecast, estimates_from_observations_microseconds_apart_are_clamped_to_what_the_planner_takes) {
  // Headings turning by 3 rad over 1 µs fit a yaw rate of 3e6 rad/s, and speeds of 0, 1000 and
  // 1000 m/s a line whose value at the last observation is 1167 m/s: both clamped (input_bounds.hpp).
  obstacle_track spinning;
  spinning.kind = obstacle_kind::pedestrian;
  spinning.history = {{0.0, {{0.0, 0.0}, 0.0}, 0.0}, {5e-7, {{0.0, 0.0}, 1.5}, 1000.0}, {1e-6, {{0.0, 0.0}, 3.0}, 1000.0}};
  const motion_estimate m = estimate_motion(spinning, 0.5, 1e-6);
  EXPECT_EQ(m.yaw_rate, largest_input_yaw_rate);
  EXPECT_EQ(m.speed, largest_input_speed);
  for (observation& o : spinning.history) o.pose.heading = -o.pose.heading;
  EXPECT_EQ(estimate_motion(spinning, 0.5, 1e-6).yaw_rate, -largest_input_yaw_rate);
}

TEST(forecast, static_obstacles_stand_still_whatever_was_observed) {
  obstacle_track wall;
  wall.kind = obstacle_kind::static_obstacle;
  wall.history = {{0.0, {{4.0, 2.0}, 0.5}, 3.0}};
  const motion_estimate m = estimate_motion(wall, 0.5, 0.0);
  EXPECT_EQ(m.speed, 0.0);
  EXPECT_EQ(m.yaw_rate, 0.0);
  const pose p = forecast_pose(m, 2.0, 3.0);
  EXPECT_EQ(p.position, (vec2{4.0, 2.0}));
}

TEST(forecast, forecast_turns_until_the_forecast_time_then_goes_straight) {
  const motion_estimate m{{{0.0, 0.0}, 0.0}, 10.0, 0.5};
  // τ = 0: straight-line extrapolation of the current velocity vector.
  const pose straight = forecast_pose(m, 0.0, 2.0);
  EXPECT_NEAR(straight.position.x, 20.0, 1e-12);
  EXPECT_NEAR(straight.position.y, 0.0, 1e-12);
  EXPECT_NEAR(straight.heading, 0.0, 1e-12);
  // τ ≥ t: on the circle of radius v/ω = 20 m about (0, 20).
  const pose turning = forecast_pose(m, 3.0, 2.0);
  EXPECT_NEAR(norm(turning.position - vec2{0.0, 20.0}), 20.0, 1e-12);
  EXPECT_NEAR(turning.heading, 1.0, 1e-12);
  // τ = 1: the arc for 1 s, then the tangent at heading 0.5 rad.
  const pose mixed = forecast_pose(m, 1.0, 2.0);
  const pose at_tau = forecast_pose(m, 1.0, 1.0);
  EXPECT_NEAR(mixed.heading, 0.5, 1e-12);
  EXPECT_NEAR(norm(mixed.position - at_tau.position), 10.0, 1e-12);
  EXPECT_NEAR(std::atan2(mixed.position.y - at_tau.position.y, mixed.position.x - at_tau.position.x), 0.5, 1e-12);
  // Speed along the forecast is v: the arc length to τ is v·τ.
  EXPECT_NEAR(norm(at_tau.position), 2.0 * 20.0 * std::sin(0.25), 1e-12);
}

}  // namespace
}  // namespace mm
