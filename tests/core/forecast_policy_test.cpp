#include "mm/forecast_policy.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "mm/maneuverability.hpp"

namespace mm {
namespace {

TEST(forecast_policy, adjustable_policy_takes_the_most_room_among_non_excluded_times) {
  const std::vector<double> brake{0.2, 0.5, 0.4, 0.9};
  const std::vector<double> accel{0.3, 0.1, 0.7, 0.2};
  EXPECT_EQ(adjustable_forecast_index(brake, accel, std::vector<std::uint8_t>{0, 0, 0, 0}), 3u);
  EXPECT_EQ(adjustable_forecast_index(brake, accel, std::vector<std::uint8_t>{0, 0, 0, 1}), 2u);
  EXPECT_EQ(adjustable_forecast_index(brake, accel, std::vector<std::uint8_t>{0, 1, 1, 1}), 0u);
}

TEST(forecast_policy, adjustable_policy_breaks_ties_toward_the_smallest_forecast_time) {
  const std::vector<double> brake{0.5, 0.8, 0.8, 0.2};
  const std::vector<double> accel{0.8, 0.1, 0.3, 0.8};
  EXPECT_EQ(adjustable_forecast_index(brake, accel, std::vector<std::uint8_t>{0, 0, 0, 0}), 0u);
}

TEST(forecast_policy, constant_policy_is_capped_at_the_last_non_excluded_time) {
  const std::vector<double> taus{0.0, 0.5, 1.0, 1.5, 2.0};
  EXPECT_EQ(constant_forecast_index(taus, 1.0, std::vector<std::uint8_t>{0, 0, 0, 0, 0}), 2u);
  EXPECT_EQ(constant_forecast_index(taus, 1.5, std::vector<std::uint8_t>{0, 0, 1, 1, 1}), 1u);
  EXPECT_EQ(constant_forecast_index(taus, 2.0, std::vector<std::uint8_t>{0, 1, 1, 1, 1}), 0u);
}

TEST(forecast_policy, family_ties_go_to_braking) {
  EXPECT_EQ(select_family(0.5, 0.5), family::brake);
  EXPECT_EQ(select_family(0.4, 0.5), family::accelerate);
  EXPECT_EQ(select_family(0.0, 0.0), family::brake);
}

TEST(forecast_policy, forecast_times_beyond_the_time_to_collision_are_excluded_but_zero_never_is) {
  const std::vector<double> taus{0.0, 0.5, 1.0, 1.5};
  EXPECT_EQ(excluded_forecast_times(taus, 0.9), (std::vector<std::uint8_t>{0, 0, 1, 1}));
  EXPECT_EQ(excluded_forecast_times(taus, 1.0), (std::vector<std::uint8_t>{0, 0, 0, 1}));
  EXPECT_EQ(excluded_forecast_times(taus, 0.0), (std::vector<std::uint8_t>{0, 1, 1, 1}));
}

}  // namespace
}  // namespace mm
