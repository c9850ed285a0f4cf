// Randomized properties of the planner (run with --seed=N --count=N), and the fast planner
// against the reference planner (spec §11).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <span>
#include <vector>

#include "mm/collision.hpp"
#include "mm/collision_sets.hpp"
#include "mm/maneuverability.hpp"
#include "mm/reference_planner.hpp"
#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

/// A random scene with random planner settings.
plan_input random_setting(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> obstacles(0, 3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  testing::scene_options options;
  options.obstacles = static_cast<std::size_t>(obstacles(rng));
  options.sensor_noise = unit(rng) < 0.5;
  plan_input in = testing::random_scene(rng, options);
  const double policy = unit(rng);
  if (policy < 0.4) {
    in.config.policy = {forecast_policy_kind::constant, 0.5 * std::floor(unit(rng) * 5.0)};
  } else if (policy < 0.6) {
    in.config.policy.kind = forecast_policy_kind::robust;
  }
  in.config.urgent_steering = unit(rng) < 0.3;
  in.config.safety_margin = unit(rng) < 0.3 ? 0.5 * unit(rng) : 0.0;
  if (unit(rng) < 0.1) in.ego.limits.steering = false;
  return in;
}

TEST(planner_properties, every_result_is_finite_bounded_and_consistent) {
  std::mt19937_64 rng(testing::property_seed());
  const std::size_t count = testing::property_count(300);
  std::size_t avoiding = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = random_setting(rng);
    const plan_result r = plan(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(r.ok()) << r.error;
    const ego_limits& l = in.ego.limits;
    ASSERT_TRUE(std::isfinite(r.command.acceleration) && std::isfinite(r.command.curvature));
    EXPECT_GE(r.command.acceleration, -l.max_deceleration);
    EXPECT_LE(r.command.acceleration, l.max_acceleration);
    EXPECT_LE(std::abs(r.command.curvature), max_curvature(in.ego.speed, l));
    ASSERT_EQ(r.mi_brake.size(), r.forecast_times.size());
    ASSERT_EQ(r.mi_accelerate.size(), r.forecast_times.size());
    ASSERT_EQ(r.excluded.size(), r.forecast_times.size());
    for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
      EXPECT_TRUE(r.mi_brake[i] >= 0.0 && r.mi_brake[i] <= 1.0) << r.mi_brake[i];
      EXPECT_TRUE(r.mi_accelerate[i] >= 0.0 && r.mi_accelerate[i] <= 1.0) << r.mi_accelerate[i];
    }
    EXPECT_EQ(r.excluded[0], 0);
    ASSERT_LT(r.forecast_index, r.forecast_times.size());
    EXPECT_EQ(r.forecast_time, r.forecast_times[r.forecast_index]) << "τ̄ on the grid";
    EXPECT_EQ(r.excluded[r.forecast_index], 0) << "τ̄ not excluded";
    EXPECT_FALSE(std::isnan(r.time_to_collision));
    EXPECT_GE(r.time_to_collision, 0.0);
    EXPECT_TRUE(r.mi_brake_selected >= 0.0 && r.mi_brake_selected <= 1.0);
    EXPECT_TRUE(r.mi_accelerate_selected >= 0.0 && r.mi_accelerate_selected <= 1.0);
    if (r.mode == planning_mode::nominal) {
      EXPECT_EQ(r.command, clamp_to_limits(in.nominal, in.ego.speed, l));
    } else {
      ++avoiding;
    }
    if (in.config.policy.kind == forecast_policy_kind::constant && r.forecast_time < in.config.policy.constant_forecast_time) {
      EXPECT_GT(r.forecast_time + in.config.forecast_step, r.time_to_collision) << "capped only by TTC";
    }
    ASSERT_EQ(r.obstacles.size(), in.obstacles.size());
  }
  EXPECT_GT(avoiding, count / 5) << "most random scenes should need avoiding, or this test checks little";
}

TEST(planner_properties, the_same_input_gives_the_same_result) {
  std::mt19937_64 rng(testing::property_seed() + 5);
  for (std::size_t trial = 0; trial < testing::property_count(40); ++trial) {
    const plan_input in = random_setting(rng);
    const plan_result a = plan(in);
    const plan_result b = plan(in);
    EXPECT_EQ(a.command, b.command);
    EXPECT_EQ(a.mi_brake, b.mi_brake);
    EXPECT_EQ(a.mi_accelerate, b.mi_accelerate);
    EXPECT_EQ(a.forecast_index, b.forecast_index);
  }
}

/// The commands of two results are the same, bit for bit, with what they rest on before any index:
/// command, mode, TTC, the excluded forecast times, and each obstacle's relevance and TTC.
void expect_same_command(const plan_result& a, const plan_result& b) {
  EXPECT_EQ(a.command, b.command);
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.excluded, b.excluded);
  EXPECT_EQ(a.time_to_collision, b.time_to_collision);
  ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
  for (std::size_t j = 0; j < a.obstacles.size(); ++j) {
    EXPECT_EQ(a.obstacles[j].relevant, b.obstacles[j].relevant) << "obstacle " << j;
    EXPECT_EQ(a.obstacles[j].time_to_collision, b.obstacles[j].time_to_collision) << "obstacle " << j;
  }
}

/// The decisions of two results are the same, bit for bit: `expect_same_command`, and the forecast
/// times, family, selected indices and what each obstacle was given.
void expect_same_decision(const plan_result& a, const plan_result& b) {
  EXPECT_EQ(a.forecast_times, b.forecast_times);
  expect_same_command(a, b);
  EXPECT_EQ(a.forecast_index, b.forecast_index);
  EXPECT_EQ(a.forecast_time, b.forecast_time);
  EXPECT_EQ(a.selected_family, b.selected_family);
  EXPECT_EQ(a.mi_brake_selected, b.mi_brake_selected);
  EXPECT_EQ(a.mi_accelerate_selected, b.mi_accelerate_selected);
  EXPECT_EQ(a.robust, b.robust);
  for (std::size_t j = 0; j < std::min(a.obstacles.size(), b.obstacles.size()); ++j) {
    EXPECT_EQ(a.obstacles[j].forecast_index, b.obstacles[j].forecast_index) << "obstacle " << j;
  }
}

/// Every field of two results is the same, bit for bit.
void expect_identical(const plan_result& a, const plan_result& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.error, b.error);
  expect_same_decision(a, b);
  EXPECT_EQ(a.mi_brake, b.mi_brake);
  EXPECT_EQ(a.mi_accelerate, b.mi_accelerate);
  EXPECT_EQ(a.collision_time_step, b.collision_time_step);
  EXPECT_EQ(a.work.bound_checks, b.work.bound_checks);
  EXPECT_EQ(a.work.distance_evaluations, b.work.distance_evaluations);
  EXPECT_EQ(a.work.refinements, b.work.refinements);
  EXPECT_EQ(a.work.assignments_evaluated, b.work.assignments_evaluated);
}

TEST(planner_properties, planning_without_the_map_column_decides_the_same_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 7);
  const std::size_t count = testing::property_count(120);
  std::size_t cheaper = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = random_setting(rng);
    plan_input decision_only = in;
    decision_only.config.map_column = false;
    const plan_result full = plan(in);
    const plan_result lean = plan(decision_only);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(full.ok() && lean.ok());
    EXPECT_TRUE(lean.mi_brake.empty() && lean.mi_accelerate.empty());
    expect_same_decision(lean, full);
    // Bound checks also count the walks of values, which can cost more without the column's values to seed them.
    cheaper += lean.work.bound_checks < full.work.bound_checks ? 1 : 0;
  }
  EXPECT_GT(cheaper, count / 10) << "leaving the map out should save work in many scenes, or this test checks little";
}

TEST(planner_properties, deciding_only_the_command_gives_the_full_step_s_command_bit_for_bit) {
  // Scenes of one to four obstacles, a third of them aimed at the ego's path, so that u_nom is now
  // safe under every forecast time and now not; the full step without the map column decides.
  std::mt19937_64 rng(testing::property_seed() + 13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(160);
  std::size_t shortcuts = 0;
  std::size_t computed = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    testing::scene_options options;
    options.obstacles = 1 + trial % 4;
    options.sensor_noise = trial % 2 == 1;
    options.conflict_probability = trial % 3 == 0 ? 0.9 : 0.3;
    plan_input in = testing::random_scene(rng, options);
    const double policy = unit(rng);
    if (policy < 0.3) {
      in.config.policy = {forecast_policy_kind::constant, 0.5 * std::floor(unit(rng) * 5.0)};
    } else if (policy < 0.5) {
      in.config.policy.kind = forecast_policy_kind::robust;
    }
    in.config.safety_margin = unit(rng) < 0.3 ? 0.5 * unit(rng) : 0.0;
    in.config.map_column = false;
    plan_input lean_input = in;
    lean_input.config.decision_only = true;
    const plan_result full = plan(in);
    const plan_result lean = plan(lean_input);
    SCOPED_TRACE("failing input:\n" + testing::describe(lean_input));
    ASSERT_TRUE(full.ok() && lean.ok());
    EXPECT_TRUE(full.indices_computed);
    expect_same_command(lean, full);
    if (lean.indices_computed) {
      expect_same_decision(lean, full);
      ++computed;
    } else {
      EXPECT_EQ(full.mode, planning_mode::nominal) << "the shortcut returns only u_nom";
      EXPECT_GT(lean.work.relevant_obstacles, 0u) << "without a relevant obstacle there is nothing to skip";
      EXPECT_EQ(lean.work.bound_checks, 0u) << "no clearance field is built";
      ++shortcuts;
    }
  }
  EXPECT_GT(shortcuts, count / 10) << "u_nom should be proven under every forecast time in many scenes";
  EXPECT_GT(computed, count / 10) << "many scenes should need the indices";
}

TEST(planner_properties, deciding_only_the_command_computes_every_index_when_the_map_column_is_wanted) {
  std::mt19937_64 rng(testing::property_seed() + 17);
  for (std::size_t trial = 0; trial < testing::property_count(30); ++trial) {
    plan_input in = testing::random_scene(rng, {1 + trial % 3, false, true, 0.3});
    in.config.decision_only = true;
    in.config.map_column = trial % 2 == 0;
    in.config.record_samples = !in.config.map_column;
    plan_input full_input = in;
    full_input.config.decision_only = false;
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    const plan_result lean = plan(in);
    EXPECT_TRUE(lean.indices_computed);
    expect_identical(lean, plan(full_input));
  }
}

TEST(planner_properties, the_fast_search_holds_every_obstacle_that_does_not_turn_at_the_first_forecast_time) {
  // Some of two or three obstacles go straight: their clearances are the same under every forecast
  // time, and both searches give them τ = 0 (the exhaustive search by its tie rule).
  std::mt19937_64 rng(testing::property_seed() + 11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(60);
  std::size_t held = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {2 + trial % 2, false});
    for (obstacle_track& track : in.obstacles) {
      if (track.kind == obstacle_kind::static_obstacle || unit(rng) < 0.5) continue;
      const observation now = track.history.back();
      track.history = testing::ctrv_history(now.pose, now.speed, 0.0, in.time);
    }
    const plan_result fast = plan(in);
    plan_input exhaustive_input = in;
    exhaustive_input.config.assignment_search = assignment_search_kind::exhaustive;
    const plan_result exhaustive = plan(exhaustive_input);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(fast.ok() && exhaustive.ok()) << fast.error << exhaustive.error;
    for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
      const obstacle_assessment& o = fast.obstacles[j];
      if (!o.relevant || o.motion.yaw_rate != 0.0) continue;
      EXPECT_EQ(o.forecast_index, 0u) << "obstacle " << j;
      EXPECT_EQ(exhaustive.obstacles[j].forecast_index, 0u) << "obstacle " << j;
      ++held;
    }
  }
  EXPECT_GT(held, count / 4) << "too few relevant obstacles that do not turn: this test checks little";
}

TEST(planner_properties, a_given_motion_equal_to_the_estimate_plans_the_same_and_another_one_is_used) {
  std::mt19937_64 rng(testing::property_seed() + 13);
  const std::size_t count = testing::property_count(60);
  std::size_t changed = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = random_setting(rng);
    if (in.obstacles.empty()) continue;
    plan_input given = in;
    for (obstacle_track& track : given.obstacles) track.motion = estimate_motion(track, in.config.history_window, in.time);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    const plan_result own = plan(in);
    const plan_result shared = plan(given);
    ASSERT_TRUE(own.ok() && shared.ok()) << own.error << shared.error;
    expect_same_decision(own, shared);
    EXPECT_EQ(own.mi_brake, shared.mi_brake);
    EXPECT_EQ(own.mi_accelerate, shared.mi_accelerate);
    // The planner uses a given motion: the first obstacle standing still where it was last seen.
    plan_input other = given;
    other.obstacles[0].motion->speed = 0.0;
    other.obstacles[0].motion->yaw_rate = 0.0;
    const plan_result moved = plan(other);
    ASSERT_TRUE(moved.ok()) << moved.error;
    EXPECT_EQ(moved.obstacles[0].motion.speed, 0.0);
    EXPECT_EQ(moved.obstacles[0].motion.yaw_rate, 0.0);
    changed += own.obstacles[0].motion.speed > 0.0 ? 1 : 0;  // the given motion differs from the estimate
  }
  EXPECT_GT(changed, count / 4) << "too few scenes whose first obstacle moves: this test checks little";
}

TEST(planner_properties, a_planner_that_reuses_its_previous_step_plans_what_plan_plans_bit_for_bit) {
  // Runs of steps of one vehicle: the speed, limits and footprint held for a few steps with new
  // poses, nominal maneuvers, obstacles and settings, then changed.
  std::mt19937_64 rng(testing::property_seed() + 13);
  const std::size_t count = testing::property_count(120);
  planner vehicle;
  plan_input previous;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = random_setting(rng);
    if (trial % 5 != 0) {
      in.ego.speed = previous.ego.speed;
      in.ego.limits = previous.ego.limits;
      in.ego.shape = previous.ego.shape;
      // Now and then another grid of as many samples per family, a·(c + 1) with its
      // nominal-curvature column (7 × 39 for 14 × 19), and back: the planner must not take one
      // for the other.
      if (trial % 4 == 1) in.config.resolution = {7, 39};
    }
    if (trial % 7 == 3) in.config.record_samples = true;
    if (trial % 11 == 5) in.config.map_column = false;
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    expect_identical(vehicle.plan(in), plan(in));
    if (::testing::Test::HasFatalFailure()) return;
    previous = in;
  }
}

/// Margin between the best and the second-best forecast time of ADJ.
double adjustable_margin(const plan_result& r) {
  std::vector<double> rooms;
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    if (!r.excluded[i]) rooms.push_back(std::max(r.mi_brake[i], r.mi_accelerate[i]));
  }
  std::sort(rooms.rbegin(), rooms.rend());
  return rooms.size() < 2 ? 1.0 : rooms[0] - rooms[1];
}

TEST(planner_properties, the_fast_indices_of_several_obstacles_are_the_union_index_of_their_brute_force_clearances) {
  // Every column of the map: the fast path reads only the values where some obstacle's clearance
  // changes sign; the union index of every obstacle's brute-force clearances (clamped to ±2 m as the
  // planner's are) must come out the same, bit for bit.
  std::mt19937_64 rng(testing::property_seed() + 41);
  const std::size_t count = testing::property_count(16);
  std::size_t several = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {2 + trial % 2, trial % 3 != 0});
    // A row longer than a word of the masks now and then, and without steering one column.
    in.config.resolution = trial % 5 == 2 ? sampling_resolution{5, 67} : sampling_resolution{9, 13};
    in.ego.limits.steering = trial % 4 != 3;
    in.config.safety_margin = trial % 4 == 1 ? 0.3 : 0.0;
    const plan_result fast = plan(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(fast.ok());
    const maneuver_samples samples =
        sample_maneuvers(in.ego, 0.0, in.config.displacement_horizon, in.config.resolution, false, false);
    const collision_window window{in.config.displacement_horizon, in.config.collision_window,
                                  fast.collision_time_step, in.config.safety_margin};
    std::vector<std::vector<clearance_set>> brute;  // [obstacle][forecast time][sample]
    for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
      if (!fast.obstacles[j].relevant) continue;
      brute.push_back(clearances_reference(in.ego, samples, {fast.obstacles[j].motion, in.obstacles[j].shape},
                                           fast.forecast_times, window));
      for (clearance_set& c : brute.back()) {
        for (double& v : c) v = std::clamp(v, -2.0, 2.0);
      }
    }
    several += brute.size() >= 2 ? 1 : 0;
    for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
      for (const family f : {family::brake, family::accelerate}) {
        const index_range r = samples.grid(f);
        std::vector<std::span<const double>> parts;
        for (const auto& sets : brute) parts.push_back(std::span(sets[i]).subspan(r.begin, r.size()));
        const double expected = maneuverability_index_of_union(samples.set(f), parts);
        ASSERT_EQ(f == family::brake ? fast.mi_brake[i] : fast.mi_accelerate[i], expected)
            << "trial " << trial << ", tau " << fast.forecast_times[i] << (f == family::brake ? ", MI-" : ", MI+");
      }
    }
  }
  EXPECT_GT(several, count / 4) << "most scenes must have several relevant obstacles";
}

TEST(planner_properties, the_robust_command_is_safe_under_every_non_excluded_forecast_time_or_adj_s_own) {
  std::mt19937_64 rng(testing::property_seed() + 71);
  const std::size_t count = testing::property_count(80);
  std::size_t robust = 0;
  std::size_t differs = 0;
  std::size_t fallbacks = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {1 + trial % 3, trial % 2 == 1});
    in.config.policy.kind = forecast_policy_kind::robust;
    const plan_result r = plan(in);
    in.config.policy.kind = forecast_policy_kind::adjustable;
    const plan_result adj = plan(in);
    SCOPED_TRACE("failing input (robust policy):\n" + testing::describe(in));
    ASSERT_TRUE(r.ok() && adj.ok()) << r.error;
    if (!r.robust) {
      ++fallbacks;
      expect_same_decision(r, adj);
      continue;
    }
    ++robust;
    differs += r.command == adj.command ? 0 : 1;
    // Proven free in continuous time, so it overlaps no obstacle at any time of a fine grid.
    const collision_window fine{in.config.displacement_horizon, in.config.collision_window, 1e-3,
                                in.config.safety_margin};
    for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
      const obstacle_assessment& o = r.obstacles[j];
      if (!o.relevant) continue;
      const std::array<forecast_obstacle, 1> alone{forecast_obstacle{o.motion, in.obstacles[j].shape}};
      for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
        if (i > 0 && r.forecast_times[i] > o.time_to_collision) continue;  // excluded for this obstacle
        const std::array<double, 1> tau{r.forecast_times[i]};
        EXPECT_EQ(first_collision_time_reference(in.ego, r.command, alone, tau, fine), no_collision)
            << "obstacle " << j << " under tau " << tau[0];
      }
    }
  }
  std::printf("robust policy: %zu of %zu decided on the robust sets (%zu unlike ADJ), %zu by ADJ\n", robust, count,
              differs, fallbacks);
  EXPECT_GT(differs, count / 20) << "the robust policy must differ from ADJ on some scenes";
  EXPECT_GT(robust, count / 4);
}

TEST(planner_properties, the_robust_indices_agree_with_the_reference_within_the_accuracy_bound) {
  std::mt19937_64 rng(testing::property_seed() + 83);
  const std::size_t count = testing::property_count(12);
  std::size_t compared = 0;
  double worst = 0.0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {1, trial % 2 == 1});
    in.config.policy.kind = forecast_policy_kind::robust;
    const plan_result fast = plan(in);
    const plan_result reference = plan_reference(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(fast.ok() && reference.ok());
    if (!fast.robust || !reference.robust) continue;  // ADJ decided: compared by the other tests
    ++compared;
    EXPECT_NEAR(fast.mi_brake_selected, reference.mi_brake_selected, 0.02);
    EXPECT_NEAR(fast.mi_accelerate_selected, reference.mi_accelerate_selected, 0.02);
    worst = std::max({worst, std::abs(fast.mi_brake_selected - reference.mi_brake_selected),
                      std::abs(fast.mi_accelerate_selected - reference.mi_accelerate_selected)});
  }
  EXPECT_GT(compared, count / 2);
  std::printf("largest robust |MI_fast - MI_reference| over %zu scenes: %.4f\n", compared, worst);
}

TEST(planner_properties, a_slow_ego_s_indices_agree_with_the_reference_within_the_accuracy_bound) {
  // Below d_max·T_h most decelerations stop the ego before T_h; the rows of both planners follow
  // the arc length there (docs/method.md §4.1). Random scenes whose ego drives at 1 to 2 m/s.
  std::mt19937_64 rng(testing::property_seed() + 57);
  const std::size_t count = testing::property_count(12);
  double worst = 0.0;
  for (std::size_t trial = 0; trial < count;) {
    const plan_input in = testing::random_scene(rng, {1, trial % 2 == 1});
    if (!(in.ego.speed >= 1.0 && in.ego.speed <= 2.0)) continue;
    ++trial;
    const plan_result fast = plan(in);
    const plan_result reference = plan_reference(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(fast.ok() && reference.ok());
    for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
      EXPECT_NEAR(fast.mi_brake[i], reference.mi_brake[i], 0.02) << "tau " << fast.forecast_times[i];
      EXPECT_NEAR(fast.mi_accelerate[i], reference.mi_accelerate[i], 0.02) << "tau " << fast.forecast_times[i];
      worst = std::max({worst, std::abs(fast.mi_brake[i] - reference.mi_brake[i]),
                        std::abs(fast.mi_accelerate[i] - reference.mi_accelerate[i])});
    }
  }
  std::printf("largest |MI_fast - MI_reference| over %zu slow scenes: %.4f\n", count, worst);
}

TEST(planner_properties, fast_planner_agrees_with_the_reference_within_the_accuracy_bound) {
  std::mt19937_64 rng(testing::property_seed() + 9);
  const std::size_t count = testing::property_count(20);
  std::size_t compared = 0;
  double worst = 0.0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {1, trial % 2 == 1});
    const plan_result fast = plan(in);
    const plan_result reference = plan_reference(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(fast.ok() && reference.ok());
    EXPECT_EQ(fast.time_to_collision == no_collision, reference.time_to_collision == no_collision);
    for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
      EXPECT_NEAR(fast.mi_brake[i], reference.mi_brake[i], 0.02) << "tau " << fast.forecast_times[i];
      EXPECT_NEAR(fast.mi_accelerate[i], reference.mi_accelerate[i], 0.02) << "tau " << fast.forecast_times[i];
      compared += reference.mi_brake[i] < 1.0 || reference.mi_accelerate[i] < 1.0 ? 1 : 0;
      worst = std::max({worst, std::abs(fast.mi_brake[i] - reference.mi_brake[i]),
                        std::abs(fast.mi_accelerate[i] - reference.mi_accelerate[i])});
    }
    // Spec §11: τ̄ and the family agree except where the reference's two candidates are within 0.02.
    if (adjustable_margin(reference) > 0.02) {
      EXPECT_EQ(fast.forecast_index, reference.forecast_index);
      if (std::abs(reference.mi_brake_selected - reference.mi_accelerate_selected) > 0.02) {
        EXPECT_EQ(fast.selected_family, reference.selected_family)
            << "reference MI- " << reference.mi_brake_selected << " MI+ " << reference.mi_accelerate_selected
            << ", fast MI- " << fast.mi_brake_selected << " MI+ " << fast.mi_accelerate_selected;
      }
    }
  }
  EXPECT_GT(compared, 0u) << "the scenes must interact for the comparison to mean anything";
  std::printf("largest |MI_fast - MI_reference| over %zu scenes: %.4f\n", count, worst);
}

}  // namespace
}  // namespace mm
