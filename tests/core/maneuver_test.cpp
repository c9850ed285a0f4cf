#include "mm/maneuver.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

TEST(maneuver, curvature_limit_is_geometric_at_low_speed_and_lateral_at_high_speed) {
  const ego_limits limits;  // R_min 5.5 m, a_lat 5 m/s²
  EXPECT_DOUBLE_EQ(max_curvature(0.0, limits), 1.0 / 5.5);
  EXPECT_DOUBLE_EQ(max_curvature(1.0, limits), 1.0 / 5.5);
  EXPECT_DOUBLE_EQ(max_curvature(10.0, limits), 5.0 / 100.0);
  const double crossover = std::sqrt(5.0 * 5.5);
  EXPECT_NEAR(max_curvature(crossover, limits), 1.0 / 5.5, 1e-12);
  ego_limits no_steering;
  no_steering.steering = false;
  EXPECT_EQ(max_curvature(10.0, no_steering), 0.0);
}

TEST(maneuver, travelled_distance_stops_at_zero_speed_and_at_the_cap) {
  EXPECT_DOUBLE_EQ(travelled_distance(10.0, 0.0, 2.0, 30.0), 20.0);
  EXPECT_DOUBLE_EQ(travelled_distance(10.0, 2.0, 1.0, 30.0), 11.0);
  // Braking at 7 m/s² from 7 m/s stops after 1 s at 3.5 m and stays there.
  EXPECT_DOUBLE_EQ(travelled_distance(7.0, -7.0, 1.0, 30.0), 3.5);
  EXPECT_DOUBLE_EQ(travelled_distance(7.0, -7.0, 3.0, 30.0), 3.5);
  EXPECT_DOUBLE_EQ(speed_after(7.0, -7.0, 3.0, 30.0), 0.0);
  // Accelerating at 3 m/s² from 28 m/s reaches the 30 m/s cap after 2/3 s.
  const double to_cap = 2.0 / 3.0;
  EXPECT_NEAR(travelled_distance(28.0, 3.0, 1.0, 30.0), 28.0 * to_cap + 1.5 * to_cap * to_cap + 30.0 * (1.0 - to_cap),
              1e-12);
  EXPECT_DOUBLE_EQ(travelled_distance(0.0, -3.0, 1.0, 30.0), 0.0);
  EXPECT_DOUBLE_EQ(travelled_distance(5.0, 1.0, 0.0, 30.0), 0.0);
}

TEST(maneuver, arc_point_lies_on_the_circle_of_the_curvature) {
  const double kappa = 0.1;
  for (const double s : {0.5, 5.0, 15.0, 31.4}) {
    const vec2 p = arc_point(kappa, s);
    // Centre of the circle at (0, 1/κ).
    EXPECT_NEAR(norm(p - vec2{0.0, 1.0 / kappa}), 1.0 / kappa, 1e-12) << s;
  }
  const vec2 quarter = arc_point(0.1, 10.0 * pi / 2.0);
  EXPECT_NEAR(quarter.x, 10.0, 1e-12);
  EXPECT_NEAR(quarter.y, 10.0, 1e-12);
  const vec2 right = arc_point(-0.1, 10.0 * pi / 2.0);
  EXPECT_NEAR(right.y, -10.0, 1e-12);
  EXPECT_EQ(arc_point(0.0, 7.0), (vec2{7.0, 0.0}));
}

TEST(maneuver, maneuver_pose_follows_the_arc_then_drives_straight) {
  const pose start{{10.0, 5.0}, pi / 2.0};
  const maneuver u{0.0, 0.1};
  const double horizon = 1.0;
  const pose at_horizon = maneuver_pose(start, 10.0, u, horizon, horizon, 30.0);
  // 10 m along a left arc of radius 10 from heading north: quarter-ish turn by 1 rad.
  const vec2 local = arc_point(0.1, 10.0);
  EXPECT_NEAR(at_horizon.position.x, 10.0 - local.y, 1e-12);
  EXPECT_NEAR(at_horizon.position.y, 5.0 + local.x, 1e-12);
  EXPECT_NEAR(at_horizon.heading, pi / 2.0 + 1.0, 1e-12);
  const pose later = maneuver_pose(start, 10.0, u, 3.0, horizon, 30.0);
  EXPECT_NEAR(later.heading, at_horizon.heading, 1e-12);
  EXPECT_NEAR(norm(later.position - at_horizon.position), 20.0, 1e-12);
  const vec2 direction = later.position - at_horizon.position;
  EXPECT_NEAR(std::atan2(direction.y, direction.x), wrap_angle(at_horizon.heading), 1e-12);
}

TEST(maneuver, the_arc_placement_of_the_travelled_distance_is_the_local_placement_bit_for_bit) {
  // Up to the horizon (straight-line turns, tiny turns on the series, stops and the speed cap).
  for (const double v0 : {0.0, 3.0, 12.5, 29.9}) {
    for (const double a : {-7.0, -1.5, 0.0, 2.0, 3.0}) {
      for (const double kappa : {-0.18, -1e-6, 0.0, 3e-5, 0.05, 0.18}) {
        for (const double t : {0.0, 0.05, 0.35, 0.999, 1.0}) {
          const maneuver u{a, kappa};
          const placement local = maneuver_local_placement(v0, u, t, 1.0, 30.0);
          const placement arc = arc_placement(travelled_distance(v0, a, t, 30.0), kappa);
          EXPECT_TRUE(local.position == arc.position && local.direction == arc.direction)
              << "v0 " << v0 << " a " << a << " kappa " << kappa << " t " << t;
        }
      }
    }
  }
}

TEST(maneuver, a_braking_maneuver_that_stops_stays_stopped) {
  const pose start{{0.0, 0.0}, 0.0};
  const maneuver u{-7.0, 0.05};
  const pose stopped = maneuver_pose(start, 5.0, u, 1.0, 1.0, 30.0);
  const pose later = maneuver_pose(start, 5.0, u, 3.0, 1.0, 30.0);
  EXPECT_NEAR(later.position.x, stopped.position.x, 1e-12);
  EXPECT_NEAR(later.position.y, stopped.position.y, 1e-12);
  EXPECT_NEAR(stopped.heading, 0.05 * 25.0 / 14.0, 1e-12);
}

TEST(maneuver, clamp_to_limits_respects_the_speed_dependent_curvature_limit) {
  const ego_limits limits;
  const maneuver clamped = clamp_to_limits({-20.0, 1.0}, 10.0, limits);
  EXPECT_DOUBLE_EQ(clamped.acceleration, -7.0);
  EXPECT_DOUBLE_EQ(clamped.curvature, 0.05);
  const maneuver inside = clamp_to_limits({1.0, -0.01}, 10.0, limits);
  EXPECT_EQ(inside, (maneuver{1.0, -0.01}));
}

}  // namespace
}  // namespace mm
