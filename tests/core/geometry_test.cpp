#include "mm/geometry.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

TEST(geometry, wrap_angle_maps_into_the_half_open_interval_minus_pi_to_pi) {
  EXPECT_NEAR(wrap_angle(3.0 * pi / 2.0), -pi / 2.0, 1e-12);
  EXPECT_NEAR(wrap_angle(-3.0 * pi / 2.0), pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(pi), pi);
  EXPECT_DOUBLE_EQ(wrap_angle(-pi), pi);
  EXPECT_NEAR(wrap_angle(6.28), 6.28 - 2.0 * pi, 1e-12);
  EXPECT_NEAR(wrap_angle(101.0 * pi + 0.25), -pi + 0.25, 1e-9);
}

/// The reference of `wrap_angle`: the remainder of 2π, with −π moved to π.
double wrap_angle_reference(double angle) {
  double wrapped = std::remainder(angle, 2.0 * pi);
  if (wrapped <= -pi) wrapped += 2.0 * pi;
  return wrapped;
}

TEST(geometry, wrap_angle_equals_its_reference_bit_for_bit) {
  std::vector<double> angles{0.0, -0.0, pi, -pi, std::nextafter(pi, 4.0), std::nextafter(pi, 0.0),
                             std::nextafter(-pi, 0.0), std::nextafter(-pi, -4.0), 2.0 * pi, -2.0 * pi,
                             3.0 * pi, -3.0 * pi, 1e-300, -1e-300, 1e6, -1e6};
  std::mt19937_64 random(20261202);
  std::uniform_real_distribution<double> near(-4.0 * pi, 4.0 * pi);
  for (int n = 0; n < 100000; ++n) angles.push_back(near(random));
  for (const double a : angles) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(wrap_angle(a)), std::bit_cast<std::uint64_t>(wrap_angle_reference(a)))
        << "angle " << a;
  }
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(geometry, sinc_and_versine_ratio_are_continuous_through_zero) {
  for (const double x : {1e-3, 1e-4, 1.0001e-4, 9.999e-5, 1e-6}) {
    EXPECT_NEAR(sinc(x), std::sin(x) / x, 1e-12) << x;
    EXPECT_NEAR(versine_ratio(x), (1.0 - std::cos(x)) / x, 1e-9) << x;
  }
  EXPECT_DOUBLE_EQ(sinc(0.0), 1.0);
  EXPECT_DOUBLE_EQ(versine_ratio(0.0), 0.0);
  EXPECT_NEAR(versine_ratio(pi), 2.0 / pi, 1e-15);
}

TEST(geometry, to_world_and_to_local_are_inverse_rigid_motions) {
  const pose frame{{3.0, -2.0}, 0.7};
  const vec2 local{1.5, -4.0};
  const vec2 world = to_world(frame, local);
  const vec2 back = to_local(frame, world);
  EXPECT_NEAR(back.x, local.x, 1e-12);
  EXPECT_NEAR(back.y, local.y, 1e-12);
  EXPECT_NEAR(norm(world - frame.position), norm(local), 1e-12);
  const vec2 ahead = to_world({{0.0, 0.0}, pi / 2.0}, {1.0, 0.0});
  EXPECT_NEAR(ahead.x, 0.0, 1e-15);
  EXPECT_NEAR(ahead.y, 1.0, 1e-15);
}

TEST(geometry, cross_is_positive_for_a_counter_clockwise_turn) {
  EXPECT_GT(cross({1.0, 0.0}, {0.0, 1.0}), 0.0);
  EXPECT_LT(cross({0.0, 1.0}, {1.0, 0.0}), 0.0);
  EXPECT_EQ(dot({1.0, 2.0}, {3.0, 4.0}), 11.0);
}

}  // namespace
}  // namespace mm
