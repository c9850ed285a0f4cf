#include "mm/displacement_set.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace mm {
namespace {

/// Area enclosed by the boundary of {arc_point(κ, s) : s ∈ [s0, s1], |κ| ≤ κm}, by the shoelace
/// formula on a finely sampled boundary: independent of the area element.
double shoelace_area(double s0, double s1, double kappa_max) {
  std::vector<vec2> boundary;
  constexpr int n = 4000;
  for (int i = 0; i <= n; ++i) boundary.push_back(arc_point(-kappa_max + 2.0 * kappa_max * i / n, s1));
  for (int i = 0; i <= n; ++i) boundary.push_back(arc_point(kappa_max, s1 - (s1 - s0) * i / n));
  for (int i = 0; i <= n; ++i) boundary.push_back(arc_point(kappa_max - 2.0 * kappa_max * i / n, s0));
  for (int i = 0; i <= n; ++i) boundary.push_back(arc_point(-kappa_max, s0 + (s1 - s0) * i / n));
  double area = 0.0;
  for (std::size_t i = 0; i < boundary.size(); ++i) area += cross(boundary[i], boundary[(i + 1) % boundary.size()]);
  return std::abs(area) / 2.0;
}

TEST(displacement_set, area_element_integrates_to_the_area_of_the_annular_sector) {
  const ego_limits limits;
  for (const double v0 : {2.0, 5.0, 11.1, 20.0}) {
    for (const family f : {family::brake, family::accelerate}) {
      const displacement_set set = available_displacements(v0, limits, 1.0, f, {11, 15});
      const double s_lo = travelled_distance(v0, set.min_acceleration, 1.0, limits.speed_cap);
      const double s_hi = travelled_distance(v0, set.max_acceleration, 1.0, limits.speed_cap);
      const double expected = shoelace_area(s_lo, s_hi, set.max_curvature);
      EXPECT_NEAR(set.area, expected, 1e-4 * expected) << "v0 " << v0 << " " << to_string(f);
      double sum = 0.0;
      for (const displacement_sample& s : set.samples) {
        EXPECT_GT(s.area_weight, 0.0);
        sum += s.area_weight;
      }
      EXPECT_NEAR(sum, set.area, 1e-12 * set.area);
      EXPECT_FALSE(set.degenerate);
    }
  }
}

TEST(displacement_set, area_element_tends_to_half_the_squared_arc_length_for_straight_paths) {
  EXPECT_DOUBLE_EQ(area_element(4.0, 0.0), 8.0);
  EXPECT_NEAR(area_element(4.0, 1e-7), 8.0, 1e-9);
  EXPECT_NEAR(area_element(4.0, 0.2), (1.0 - std::cos(0.8)) / 0.04, 1e-12);
  EXPECT_NEAR(area_element_primitive(3.0, 0.0), 4.5, 1e-15);
  EXPECT_NEAR(area_element_primitive(3.0, 0.3), (3.0 - std::sin(0.9) / 0.3) / 0.09, 1e-12);
}

TEST(displacement_set, grid_spans_the_limits_and_includes_zero_acceleration_and_straight_ahead) {
  const ego_limits limits;
  const displacement_set brake = available_displacements(10.0, limits, 1.0, family::brake, {11, 15});
  ASSERT_EQ(brake.samples.size(), 11u * 15u);
  EXPECT_EQ(brake.samples.front().u, (maneuver{-7.0, -0.05}));
  EXPECT_DOUBLE_EQ(brake.samples.back().u.acceleration, 0.0);
  EXPECT_DOUBLE_EQ(brake.samples.back().u.curvature, 0.05);
  EXPECT_DOUBLE_EQ(brake.samples[7].u.curvature, 0.0);
  const displacement_set accel = available_displacements(10.0, limits, 1.0, family::accelerate, {11, 15});
  EXPECT_DOUBLE_EQ(accel.samples.front().u.acceleration, 0.0);
  EXPECT_DOUBLE_EQ(accel.samples.back().u.acceleration, 3.0);
  // The end point of a straight full-acceleration maneuver: 10 + 1.5 m ahead.
  EXPECT_NEAR(accel.samples[10 * 15 + 7].end_point.x, 11.5, 1e-12);
  EXPECT_NEAR(accel.samples[10 * 15 + 7].end_point.y, 0.0, 1e-12);
}

TEST(displacement_set, rows_are_evenly_spaced_in_the_arc_length_where_the_ego_stops_or_reaches_the_cap) {
  // Braking from below d_max·T_h stops the ego before T_h for the harder decelerations, and from
  // near the cap accelerating reaches it: s(a) has a kink, and the rows follow s, not a.
  const ego_limits limits;
  for (const auto& [v0, f] : {std::pair{0.5, family::brake}, std::pair{1.24, family::brake}, std::pair{3.0, family::brake},
                              std::pair{6.9, family::brake}, std::pair{28.5, family::accelerate}}) {
    for (const std::size_t rows : {3u, 15u, 41u}) {
      const displacement_set set = available_displacements(v0, limits, 1.0, f, {rows, 5});
      const auto arc_length = [&](std::size_t ia) {
        return travelled_distance(v0, set.samples[ia * set.curvature_count].u.acceleration, 1.0, limits.speed_cap);
      };
      const double s_lo = travelled_distance(v0, set.min_acceleration, 1.0, limits.speed_cap);
      const double s_hi = travelled_distance(v0, set.max_acceleration, 1.0, limits.speed_cap);
      EXPECT_EQ(set.samples.front().u.acceleration, set.min_acceleration);
      EXPECT_EQ(set.samples.back().u.acceleration, set.max_acceleration);
      for (std::size_t ia = 0; ia < rows; ++ia) {
        const double expected = s_lo + (s_hi - s_lo) * static_cast<double>(ia) / static_cast<double>(rows - 1);
        EXPECT_NEAR(arc_length(ia), expected, 1e-12 * s_hi) << "v0 " << v0 << " row " << ia << " of " << rows;
      }
      const double expected_area = shoelace_area(s_lo, s_hi, set.max_curvature);
      EXPECT_NEAR(set.area, expected_area, 1e-4 * expected_area) << "v0 " << v0;
    }
  }
}

TEST(displacement_set, where_the_arc_length_is_affine_in_the_acceleration_the_rows_are_evenly_spaced_in_it) {
  // No stop and no cap within T_h: the same rows, computed in a, bit for bit.
  const ego_limits limits;
  for (const auto& [v0, f] : {std::pair{7.5, family::brake}, std::pair{12.0, family::brake}, std::pair{1.0, family::accelerate},
                              std::pair{20.0, family::accelerate}}) {
    const displacement_set set = available_displacements(v0, limits, 1.0, f, {15, 5});
    const double step = (set.max_acceleration - set.min_acceleration) / 14.0;
    for (std::size_t ia = 0; ia < 15; ++ia) {
      const double expected = ia == 14 ? set.max_acceleration : set.min_acceleration + step * static_cast<double>(ia);
      EXPECT_EQ(set.samples[ia * set.curvature_count].u.acceleration, expected) << "v0 " << v0 << " row " << ia;
    }
  }
}

TEST(displacement_set, brake_family_of_a_stopped_ego_is_degenerate_with_equal_weights) {
  const displacement_set set = available_displacements(0.0, ego_limits{}, 1.0, family::brake, {5, 3});
  EXPECT_TRUE(set.degenerate);
  EXPECT_EQ(set.area, 0.0);
  for (const displacement_sample& s : set.samples) {
    EXPECT_DOUBLE_EQ(s.area_weight, 1.0 / 15.0);
    EXPECT_EQ(s.end_point, (vec2{0.0, 0.0}));
  }
  const displacement_set accel = available_displacements(0.0, ego_limits{}, 1.0, family::accelerate, {5, 3});
  EXPECT_FALSE(accel.degenerate);
  EXPECT_GT(accel.area, 0.0);
}

TEST(displacement_set, without_steering_a_single_straight_column_weighs_the_limit_of_the_area) {
  ego_limits limits;
  limits.steering = false;
  const displacement_set set = available_displacements(10.0, limits, 1.0, family::brake, {8, 15});
  ASSERT_EQ(set.curvature_count, 1u);
  ASSERT_EQ(set.samples.size(), 8u);
  // Weights are ∫ s²/2 ds over each cell; they sum to (s_hi³ − s_lo³)/6.
  EXPECT_NEAR(set.area, (1000.0 - std::pow(6.5, 3.0)) / 6.0, 1e-9);
  for (const displacement_sample& s : set.samples) EXPECT_EQ(s.u.curvature, 0.0);
  // The ratio of the steering-disabled weights is the κ_max → 0 limit of the area ratio.
  ego_limits narrow;
  narrow.max_lateral_acceleration = 1e-6;
  const displacement_set thin = available_displacements(10.0, narrow, 1.0, family::brake, {8, 1});
  for (std::size_t i = 0; i < set.samples.size(); ++i) {
    EXPECT_NEAR(set.samples[i].area_weight / set.area, thin.samples[i].area_weight / thin.area, 1e-9);
  }
}

}  // namespace
}  // namespace mm
