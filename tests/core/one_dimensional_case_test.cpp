// Spec §10: with steering disabled and two vehicles crossing at right angles, the safe
// accelerations of the two families are intervals given in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mm/planner.hpp"
#include "mm/reference_planner.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double car_length = 4.5;
constexpr double car_width = 1.8;

struct crossing {
  double speed_a;      ///< V_A, east along y = 0 from x = 0 [m/s]
  double speed_b;      ///< V_B, south along x = x_road [m/s]
  double x_road;       ///< centre line of B's road [m]
  double y_b;          ///< B's current position [m]
};

/// The closed form of spec §10 (paper Fig. 1) for the scene `c`.
struct closed_form {
  double dt1;   ///< B's front reaches A's near edge
  double dt2;   ///< B's rear clears A's far edge
  double d_a1;  ///< A must cover this by Δt1 to pass first (its rear clears B's road)
  double d_a2;  ///< A may cover at most this by Δt2 to yield (its front stays short of B's road)
  double a1;    ///< yield: a ≤ a1
  double a2;    ///< pass: a ≥ a2
  double yield_bound;  ///< a1 corrected for stop-at-zero: the largest a that yields
};

closed_form solve(const crossing& c) {
  closed_form f{};
  f.dt1 = (c.y_b - car_length / 2.0 - car_width / 2.0) / c.speed_b;
  f.dt2 = (c.y_b + car_length / 2.0 + car_width / 2.0) / c.speed_b;
  f.d_a1 = c.x_road + car_width / 2.0 + car_length / 2.0;
  f.d_a2 = c.x_road - car_width / 2.0 - car_length / 2.0;
  f.a1 = 2.0 * (f.d_a2 - c.speed_a * f.dt2) / (f.dt2 * f.dt2);
  f.a2 = 2.0 * (f.d_a1 - c.speed_a * f.dt1) / (f.dt1 * f.dt1);
  // A maneuver that stops before Δt2 covers v²/(2|a|) instead of v·Δt + a·Δt²/2.
  f.yield_bound = f.a1 >= -c.speed_a / f.dt2 ? f.a1 : -c.speed_a * c.speed_a / (2.0 * f.d_a2);
  return f;
}

plan_input scene(const crossing& c) {
  plan_input in;
  in.time = 0.0;
  in.ego.speed = c.speed_a;
  in.ego.limits.steering = false;
  // The closed form assumes constant acceleration until B has passed: hold it for the whole window.
  in.config.displacement_horizon = 3.0;
  in.config.collision_window = 3.0;
  in.config.resolution = {141, 1};
  in.config.max_time_step = 0.002;
  in.config.record_samples = true;
  obstacle_track b;
  b.id = 2;
  b.history = testing::ctrv_history({{c.x_road, c.y_b}, -pi / 2.0}, c.speed_b, 0.0, in.time);
  in.obstacles.push_back(b);
  return in;
}

/// Checks the safe accelerations of both families against the closed form; returns the bounds seen.
void check(const crossing& c, bool braking_possible, bool accelerating_possible) {
  const closed_form f = solve(c);
  ASSERT_LT(f.dt2, 3.0) << "B must have passed within the collision window";
  ASSERT_GT(f.d_a2, 0.0);
  const plan_input in = scene(c);
  const plan_result r = plan(in);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_TRUE(r.samples);
  const sample_snapshot& s = *r.samples;
  const ego_limits& l = in.ego.limits;
  const double brake_step = l.max_deceleration / 140.0;
  // Tolerance: the acceleration step plus what the 0.002 s time sampling can shift the boundary.
  const double tolerance = 1.5 * brake_step + 0.05;
  const double yield_max = std::min(0.0, f.yield_bound);
  const double pass_min = std::max(0.0, f.a2);
  std::size_t checked = 0;
  double largest_safe_brake = -1e9;
  double smallest_safe_accel = 1e9;
  for (std::size_t m = 0; m < s.maneuvers.size(); ++m) {
    if (s.on_nominal_curvature[m]) continue;
    const double a = s.maneuvers[m].acceleration;
    const bool safe = s.safe_by_forecast[0][m] != 0;
    const bool expected = s.families[m] == family::brake ? (a <= yield_max || a >= f.a2) : (a >= pass_min || a <= f.yield_bound);
    const double distance_to_bound = s.families[m] == family::brake ? std::min(std::abs(a - yield_max), std::abs(a - f.a2))
                                                                   : std::min(std::abs(a - pass_min), std::abs(a - f.yield_bound));
    if (distance_to_bound > tolerance) {
      EXPECT_EQ(safe, expected) << to_string(s.families[m]) << " a = " << a << " a1 = " << f.a1
                                << " yield bound = " << f.yield_bound << " a2 = " << f.a2;
      ++checked;
    }
    if (safe && s.families[m] == family::brake) largest_safe_brake = std::max(largest_safe_brake, a);
    if (safe && s.families[m] == family::accelerate) smallest_safe_accel = std::min(smallest_safe_accel, a);
  }
  EXPECT_GT(checked, 250u);
  if (braking_possible) {
    EXPECT_NEAR(largest_safe_brake, yield_max, tolerance) << "brake family: [−d_max, min(0, a1)]";
  } else {
    EXPECT_EQ(largest_safe_brake, -1e9) << "braking cannot avoid B: a1 = " << f.yield_bound;
    EXPECT_EQ(r.mi_brake[0], 0.0);
  }
  if (accelerating_possible) {
    EXPECT_NEAR(smallest_safe_accel, pass_min, tolerance) << "accelerate family: [max(0, a2), a_max]";
  } else {
    EXPECT_EQ(smallest_safe_accel, 1e9) << "accelerating cannot avoid B: a2 = " << f.a2;
    EXPECT_EQ(r.mi_accelerate[0], 0.0);
  }
}

TEST(one_dimensional_case, only_yielding_works_when_b_arrives_early) {
  const crossing c{11.1, 10.0, 20.0, 15.0};  // a1 ≈ −2.0, a2 ≈ 14 > a_max
  const closed_form f = solve(c);
  EXPECT_NEAR(f.a1, -2.0, 0.05);
  EXPECT_GT(f.a2, 3.0);
  check(c, true, false);
}

TEST(one_dimensional_case, yielding_and_passing_both_work_when_b_arrives_late) {
  const crossing c{11.1, 10.0, 22.0, 23.15};  // a1 ≈ −3.0, a2 ≈ 1.5
  const closed_form f = solve(c);
  EXPECT_NEAR(f.a2, 1.475, 0.01);
  check(c, true, true);
}

TEST(one_dimensional_case, only_passing_works_when_braking_cannot_stop_short) {
  const crossing c{15.0, 12.0, 12.0, 14.85};  // stopping needs 12.7 m/s², a2 ≈ 1.1
  const closed_form f = solve(c);
  EXPECT_LT(f.yield_bound, -7.0);
  EXPECT_GT(f.a2, 0.0);
  EXPECT_LT(f.a2, 3.0);
  check(c, false, true);
}

TEST(one_dimensional_case, stop_at_zero_moves_the_yield_bound_below_the_closed_form) {
  const crossing c{8.0, 8.0, 12.0, 16.85};  // Δt2 = 2.5 s: the yielding A stops before B has passed; a2 ≈ 0.99
  const closed_form f = solve(c);
  EXPECT_LT(f.a1, -c.speed_a / f.dt2);
  EXPECT_LT(f.yield_bound, f.a1);
  check(c, true, true);
}

TEST(one_dimensional_case, neither_works_when_b_arrives_too_early_to_pass_and_too_close_to_stop) {
  const crossing c{15.0, 10.0, 12.0, 11.85};
  const closed_form f = solve(c);
  EXPECT_LT(f.yield_bound, -7.0);
  EXPECT_GT(f.a2, 3.0);
  check(c, false, false);
  const plan_result r = plan(scene(c));
  EXPECT_EQ(r.mode, planning_mode::near_crash);
}

TEST(one_dimensional_case, the_reference_samples_a_family_without_steering_on_a_dense_segment) {
  // A family without steering is a segment: the reference spends its density along it.
  ego_limits steering;
  ego_limits straight;
  straight.steering = false;
  const reference_resolution resolution;
  EXPECT_EQ(reference_grid(steering, resolution).accelerations, 41u);
  EXPECT_EQ(reference_grid(steering, resolution).curvatures, 121u);
  EXPECT_EQ(reference_grid(straight, resolution).accelerations, 641u);
  EXPECT_EQ(reference_grid(straight, resolution).curvatures, 1u);
  const reference_resolution coarse{{11, 15}, 1e-4, 21};
  EXPECT_EQ(reference_grid(straight, coarse).accelerations, 21u);
}

}  // namespace
}  // namespace mm
