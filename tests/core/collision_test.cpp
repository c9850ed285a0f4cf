#include "mm/collision.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

ego_state ego_east(double speed) {
  ego_state ego;
  ego.pose = {{0.0, 0.0}, 0.0};
  ego.speed = speed;
  return ego;
}

TEST(collision, sample_times_cover_the_window_and_end_exactly_at_it) {
  const std::vector<double> times = sample_times(3.0, 0.05);
  ASSERT_EQ(times.size(), 61u);
  EXPECT_EQ(times.front(), 0.0);
  EXPECT_EQ(times.back(), 3.0);
  const std::vector<double> uneven = sample_times(1.0, 0.3);
  ASSERT_EQ(uneven.size(), 5u);
  EXPECT_EQ(uneven.back(), 1.0);
}

TEST(collision, time_to_collision_with_a_vehicle_standing_ahead_matches_the_gap_over_the_speed) {
  const ego_state ego = ego_east(10.0);
  const forecast_obstacle parked{{{{25.0, 0.0}, 0.0}, 0.0, 0.0}, rectangle{4.5, 1.8}};
  const collision_window window{1.0, 3.0, 0.05, 0.0};
  // Fronts meet when the ego has covered 25 − 4.5 = 20.5 m.
  EXPECT_NEAR(time_to_collision(ego, {0.0, 0.0}, parked, window), 2.05, 2e-4);
  EXPECT_EQ(time_to_collision(ego, {-7.0, 0.0}, parked, window), no_collision);
  const collision_window wide{1.0, 3.0, 0.05, 1.0};
  EXPECT_NEAR(time_to_collision(ego, {0.0, 0.0}, parked, wide), 1.95, 2e-4);
}

TEST(collision, crossing_vehicle_collides_under_straight_forecast_but_not_after_it_has_turned_away) {
  const ego_state ego = ego_east(10.0);
  // B heads south toward the ego's lane at x = 20, turning right (clockwise) at 0.8 rad/s.
  const forecast_obstacle b{{{{20.0, 12.0}, -pi / 2.0}, 8.0, -0.8}, rectangle{4.5, 1.8}};
  const collision_window window{1.0, 3.0, 0.02, 0.0};
  const std::array<forecast_obstacle, 1> obstacles{b};
  const std::array<double, 1> straight{0.0};
  const std::array<double, 1> turning{2.0};
  EXPECT_TRUE(maneuver_collides(ego, {0.0, 0.0}, obstacles, straight, window));
  EXPECT_FALSE(maneuver_collides(ego, {0.0, 0.0}, obstacles, turning, window));
  // First collision under the straight forecast: B's front reaches y = 0.9 at (12 − 2.25 − 0.9)/8 s.
  const double t = first_collision_time(ego, {0.0, 0.0}, obstacles, straight, window);
  EXPECT_GT(t, (12.0 - 2.25 - 0.9) / 8.0 - 0.02);
  EXPECT_LT(t, 2.0);
}

TEST(collision, verification_catches_a_contact_between_sample_times) {
  const ego_state stopped = ego_east(0.0);
  // A walker crossing 0.3 m in front of the car at 20 m/s: in contact from t ≈ 0.043 s to 0.157 s,
  // between the samples 0 and 0.2 s of a coarse window.
  const forecast_obstacle fast_walker{{{{2.55, 2.0}, -pi / 2.0}, 20.0, 0.0}, disc{0.35}};
  const collision_window coarse{1.0, 3.0, 0.2, 0.0};
  const std::array<forecast_obstacle, 1> obstacles{fast_walker};
  const std::array<double, 1> taus{0.0};
  EXPECT_FALSE(maneuver_collides(stopped, {0.0, 0.0}, obstacles, taus, coarse)) << "the samples miss it";
  EXPECT_FALSE(verified_collision_free(stopped, {0.0, 0.0}, obstacles, taus, coarse));
  const collision_window fine{1.0, 3.0, 0.01, 0.0};
  EXPECT_TRUE(maneuver_collides(stopped, {0.0, 0.0}, obstacles, taus, fine));
  // Passing 1.25 m in front instead: proven free.
  const std::array<forecast_obstacle, 1> clear{forecast_obstacle{{{{3.5, 2.0}, -pi / 2.0}, 20.0, 0.0}, disc{0.35}}};
  EXPECT_TRUE(verified_collision_free(stopped, {0.0, 0.0}, clear, taus, coarse));
  // Braking hard in front of a crossing car is proven free; driving on is not.
  const std::array<forecast_obstacle, 1> car{forecast_obstacle{{{{20.0, 12.0}, -pi / 2.0}, 8.0, 0.0}, rectangle{}}};
  EXPECT_TRUE(verified_collision_free(ego_east(10.0), {-7.0, 0.0}, car, taus, coarse));
  EXPECT_FALSE(verified_collision_free(ego_east(10.0), {0.0, 0.0}, car, taus, coarse));
}

TEST(collision, a_proof_whose_last_step_is_cut_short_by_the_window_s_end_is_not_a_contact) {
  const ego_state stopped = ego_east(0.0);
  // A walker passing along the stopped car's left side at 1.5 m/s, its clearance c constant while it
  // is beside the car: each step of the proof is c / 1.5 s, two of them end 0.5 ms before T_c = 1 s,
  // and the third is cut to those 0.5 ms, below the resolution of 1 ms.
  const double step = (1.0 - 0.5e-3) / 2.0;
  const double clearance = 1.5 * step;
  const std::array<forecast_obstacle, 1> beside{
      forecast_obstacle{{{{-1.0, 0.9 + 0.35 + clearance}, 0.0}, 1.5, 0.0}, disc{0.35}}};
  const std::array<double, 1> taus{0.0};
  const collision_window window{1.0, 1.0, 0.05, 0.0};
  EXPECT_TRUE(verified_collision_free(stopped, {0.0, 0.0}, beside, taus, window, 1e-3));
  EXPECT_TRUE(verified_collision_free_reference(stopped, {0.0, 0.0}, beside, taus, window, 1e-3));
  // Within the resolution of the car, a step shorter than it still counts as not proven.
  const std::array<forecast_obstacle, 1> grazing{
      forecast_obstacle{{{{-1.0, 0.9 + 0.35 + 1e-3}, 0.0}, 1.5, 0.0}, disc{0.35}}};
  EXPECT_FALSE(verified_collision_free(stopped, {0.0, 0.0}, grazing, taus, window, 1e-3));
  EXPECT_FALSE(verified_collision_free_reference(stopped, {0.0, 0.0}, grazing, taus, window, 1e-3));
}

TEST(collision, tunneling_step_is_the_smallest_dimension_over_the_largest_relative_speed) {
  const ego_state ego = ego_east(10.0);
  const forecast_obstacle walker{{{{0.0, 0.0}, 0.0}, 1.5, 0.0}, disc{0.35}};
  const collision_window window{1.0, 3.0, 0.05, 0.0};
  EXPECT_NEAR(tunneling_time_step(ego, walker, window), 0.7 / (13.0 + 1.5), 1e-12);
}

}  // namespace
}  // namespace mm
