#include "mm/sim/metrics.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

namespace {

using namespace mm::sim;
constexpr double pi = std::numbers::pi;

TEST(sim_metrics, constant_velocity_ttc_of_a_head_on_approach) {
  // Fronts 10 m apart, closing at 20 m/s: contact after 0.5 s.
  const auto ttc = constant_velocity_ttc(mm::rectangle{}, {{0.0, 0.0}, 0.0}, {10.0, 0.0}, mm::rectangle{},
                                         {{14.5, 0.0}, pi}, {-10.0, 0.0});
  ASSERT_TRUE(ttc.has_value());
  EXPECT_NEAR(*ttc, 0.5, 2e-6);
}

TEST(sim_metrics, constant_velocity_ttc_of_a_crossing_and_of_a_miss) {
  // B crosses 20 m ahead from the right at 10 m/s; A at 10 m/s. A's front reaches B's near side
  // (x = 19.1) at 1.685 s; B's far end reaches A's near side (y = −0.9) at (20 − 2.25 − 0.9)/10.
  const mm::pose a{{0.0, 0.0}, 0.0};
  const mm::pose b{{20.0, -20.0}, pi / 2.0};
  const auto ttc = constant_velocity_ttc(mm::rectangle{}, a, {10.0, 0.0}, mm::rectangle{}, b, {0.0, 10.0});
  ASSERT_TRUE(ttc.has_value());
  EXPECT_NEAR(*ttc, std::max((19.1 - 2.25) / 10.0, (20.0 - 2.25 - 0.9) / 10.0), 2e-6);
  // B twice as fast: its rear has passed y = 0.9 before A's front arrives — a miss.
  EXPECT_FALSE(constant_velocity_ttc(mm::rectangle{}, a, {10.0, 0.0}, mm::rectangle{}, b, {0.0, 30.0}).has_value());
  // Moving apart, or not moving relative to each other.
  EXPECT_FALSE(constant_velocity_ttc(mm::rectangle{}, a, {-5.0, 0.0}, mm::disc{}, {{10.0, 0.0}, 0.0}, {0.0, 0.0})
                   .has_value());
  EXPECT_FALSE(constant_velocity_ttc(mm::rectangle{}, a, {5.0, 0.0}, mm::disc{}, {{10.0, 0.0}, 0.0}, {5.0, 0.0})
                   .has_value());
  // Already overlapping.
  EXPECT_EQ(*constant_velocity_ttc(mm::rectangle{}, a, {}, mm::disc{}, {{1.0, 0.0}, 0.0}, {}), 0.0);
}

TEST(sim_metrics, quantiles_use_the_nearest_rank) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 50.5);
  EXPECT_DOUBLE_EQ(quantile(v, 0.99), 99.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 100.0);
  const std::vector<double> odd{3.0, 1.0, 2.0};
  EXPECT_DOUBLE_EQ(quantile(odd, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile(odd, 0.99), 3.0);
  EXPECT_DOUBLE_EQ(quantile(std::vector<double>{}, 0.5), 0.0);
  EXPECT_EQ(to_string(bypass_side::left), "left");
}

}  // namespace
