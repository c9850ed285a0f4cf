#include "mm/assignment_search.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "mm/collision_sets.hpp"
#include "mm/forecast_policy.hpp"
#include "mm/maneuverability.hpp"
#include "property.hpp"

namespace mm {
namespace {

ego_state moving_ego() {
  ego_state ego;
  ego.speed = 10.0;
  return ego;
}

/// Collision sets per obstacle and forecast time, and the search problem over them.
struct synthetic {
  const maneuver_samples* samples;
  std::vector<std::vector<sample_mask>> collision_sets;
  assignment_problem problem;
};

double room_of(const maneuver_samples& samples, const sample_mask& colliding) {
  const maneuverability_pair mi = maneuverability_indices(samples, colliding);
  return std::max(mi.brake, mi.accelerate);
}

/// Random collision sets: each obstacle hits a random band of accelerations that drifts with τ.
std::unique_ptr<synthetic> random_problem(std::mt19937_64& rng, const maneuver_samples& samples, std::size_t obstacles) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto out = std::make_unique<synthetic>();
  out->samples = &samples;
  assignment_problem& problem = out->problem;
  for (std::size_t j = 0; j < obstacles; ++j) {
    const double centre = -7.0 + 10.0 * unit(rng);
    const double drift = 4.0 * (unit(rng) - 0.5);
    const double width = 0.5 + 3.0 * unit(rng);
    const double side = unit(rng) - 0.5;
    std::vector<sample_mask> sets;
    for (std::size_t i = 0; i < 9; ++i) {
      sample_mask mask(samples.size());
      const double c = centre + drift * static_cast<double>(i) / 8.0;
      for (std::size_t m = 0; m < samples.size(); ++m) {
        const maneuver& u = samples.maneuvers[m];
        if (std::abs(u.acceleration - c) < width / 2.0 && u.curvature * side >= -0.01) mask.set(m);
      }
      sets.push_back(std::move(mask));
    }
    out->collision_sets.push_back(std::move(sets));
    const std::size_t allowed = 1 + static_cast<std::size_t>(unit(rng) * 9.0) % 9;
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < allowed; ++i) candidates.push_back(i);
    problem.candidates.push_back(std::move(candidates));
  }
  synthetic* raw = out.get();
  problem.room = [raw](std::span<const std::size_t> index) {
    sample_mask colliding(raw->samples->size());
    for (std::size_t j = 0; j < index.size(); ++j) colliding |= raw->collision_sets[j][index[j]];
    return room_of(*raw->samples, colliding);
  };
  problem.room_alone = [raw](std::size_t j, std::size_t i) { return room_of(*raw->samples, raw->collision_sets[j][i]); };
  return out;
}

TEST(assignment_search, one_obstacle_reduces_to_the_adjustable_policy) {
  const maneuver_samples samples = sample_maneuvers(moving_ego(), 0.0, 1.0, {11, 9});
  std::mt19937_64 rng(testing::property_seed());
  for (int trial = 0; trial < 50; ++trial) {
    const auto synthetic = random_problem(rng, samples, 1);
    const assignment_problem& problem = synthetic->problem;
    std::vector<double> brake;
    std::vector<double> accel;
    std::vector<std::uint8_t> excluded;
    for (std::size_t i = 0; i < 9; ++i) {
      const maneuverability_pair mi = maneuverability_indices(samples, synthetic->collision_sets[0][i]);
      brake.push_back(mi.brake);
      accel.push_back(mi.accelerate);
      excluded.push_back(i < problem.candidates[0].size() ? 0 : 1);
    }
    const std::size_t adj = adjustable_forecast_index(brake, accel, excluded);
    EXPECT_EQ(exhaustive_assignment_search(problem).forecast_index[0], adj);
    EXPECT_EQ(coordinate_ascent_assignment_search(problem).forecast_index[0], adj);
  }
}

TEST(assignment_search, exhaustive_search_visits_every_assignment_and_finds_the_maximum) {
  const maneuver_samples samples = sample_maneuvers(moving_ego(), 0.0, 1.0, {11, 9});
  std::mt19937_64 rng(testing::property_seed() + 1);
  for (int trial = 0; trial < 20; ++trial) {
    const auto synthetic = random_problem(rng, samples, 3);
    const assignment_problem& problem = synthetic->problem;
    const forecast_assignment best = exhaustive_assignment_search(problem);
    EXPECT_EQ(best.evaluations, assignment_count(problem));
    double maximum = -1.0;
    for (const std::size_t a : problem.candidates[0]) {
      for (const std::size_t b : problem.candidates[1]) {
        for (const std::size_t c : problem.candidates[2]) {
          maximum = std::max(maximum, problem.room(std::vector<std::size_t>{a, b, c}));
        }
      }
    }
    EXPECT_DOUBLE_EQ(best.room, maximum);
    EXPECT_DOUBLE_EQ(problem.room(best.forecast_index), best.room);
  }
}

TEST(assignment_search, coordinate_ascent_never_beats_the_exhaustive_optimum_and_usually_reaches_it) {
  const maneuver_samples samples = sample_maneuvers(moving_ego(), 0.0, 1.0, {11, 9});
  std::mt19937_64 rng(testing::property_seed() + 2);
  const std::size_t count = testing::property_count(200);
  std::size_t close = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const auto synthetic = random_problem(rng, samples, 2 + trial % 2);
    const assignment_problem& problem = synthetic->problem;
    const forecast_assignment exhaustive = exhaustive_assignment_search(problem);
    const forecast_assignment fast = coordinate_ascent_assignment_search(problem);
    EXPECT_LE(fast.room, exhaustive.room + 1e-12);
    EXPECT_DOUBLE_EQ(problem.room(fast.forecast_index), fast.room);
    for (std::size_t j = 0; j < problem.candidates.size(); ++j) {
      EXPECT_LT(fast.forecast_index[j], problem.candidates[j].size()) << "only allowed forecast times";
    }
    if (fast.room >= exhaustive.room - 0.02) ++close;
  }
  EXPECT_GE(static_cast<double>(close), 0.95 * static_cast<double>(count));
}

TEST(assignment_search, a_problem_with_one_assignment_is_answered_without_a_climb) {
  const maneuver_samples samples = sample_maneuvers(moving_ego(), 0.0, 1.0, {11, 9});
  std::mt19937_64 rng(testing::property_seed() + 3);
  const auto synthetic = random_problem(rng, samples, 3);
  assignment_problem problem = synthetic->problem;
  problem.candidates = {{0}, {0}, {0}};
  int rough_calls = 0;
  problem.rough_room = [&](std::span<const std::size_t>) { return ++rough_calls, 0.5; };
  problem.rough_room_alone = [&](std::size_t, std::size_t) { return ++rough_calls, 0.5; };
  const forecast_assignment fast = coordinate_ascent_assignment_search(problem);
  EXPECT_EQ(fast.forecast_index, (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_DOUBLE_EQ(fast.room, problem.room(fast.forecast_index));
  EXPECT_EQ(fast.evaluations, 1u);
  EXPECT_EQ(rough_calls, 0);
  EXPECT_EQ(exhaustive_assignment_search(problem).forecast_index, fast.forecast_index);
}

TEST(assignment_search, no_obstacle_leaves_all_the_room) {
  const maneuver_samples samples = sample_maneuvers(moving_ego(), 0.0, 1.0, {5, 3});
  assignment_problem problem;
  problem.room = [&](std::span<const std::size_t>) { return room_of(samples, sample_mask(samples.size())); };
  problem.room_alone = [](std::size_t, std::size_t) { return 1.0; };
  EXPECT_DOUBLE_EQ(exhaustive_assignment_search(problem).room, 1.0);
  EXPECT_DOUBLE_EQ(coordinate_ascent_assignment_search(problem).room, 1.0);
}

}  // namespace
}  // namespace mm
