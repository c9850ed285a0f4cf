#include "mm/plan_comparison.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace mm::plan_comparison {
namespace {

/// A plan whose map column has three forecast times and whose pick is (`index`, `f`).
plan_result picked(std::size_t index, family f) {
  plan_result r;
  r.forecast_times = {0.0, 1.0, 2.0};
  r.mi_brake = {0.70, 0.60, 0.50};
  r.mi_accelerate = {0.68, 0.71, 0.65};
  r.forecast_index = index;
  r.selected_family = f;
  return r;
}

TEST(plan_comparison, the_same_pick_falls_short_by_nothing) {
  EXPECT_EQ(pick_shortfall(picked(1, family::accelerate), picked(1, family::accelerate)), 0.0);
}

TEST(plan_comparison, a_pick_falls_short_by_the_reference_s_own_indices) {
  const plan_result reference = picked(1, family::accelerate);
  // Another forecast time, another family: MI+(1) − MI−(0) of the reference.
  EXPECT_NEAR(pick_shortfall(picked(0, family::brake), reference), 0.01, 1e-12);
  // The same forecast time, the other family: the reference's family margin there.
  EXPECT_NEAR(pick_shortfall(picked(1, family::brake), reference), 0.11, 1e-12);
  // Another forecast time, the same family.
  EXPECT_NEAR(pick_shortfall(picked(2, family::accelerate), reference), 0.06, 1e-12);
}

TEST(plan_comparison, relevant_obstacles_counts_only_the_relevant_ones) {
  plan_result r;
  EXPECT_EQ(relevant_obstacles(r), 0u);
  r.obstacles.resize(3);
  r.obstacles[0].relevant = true;
  r.obstacles[2].relevant = true;
  EXPECT_EQ(relevant_obstacles(r), 2u);
}

TEST(plan_comparison, a_pick_outside_the_reference_s_map_column_is_an_error) {
  EXPECT_THROW(pick_shortfall(picked(3, family::brake), picked(1, family::accelerate)), std::invalid_argument);
}

}  // namespace
}  // namespace mm::plan_comparison
