// The time to collision by conservative advancement, the first collision times and the
// continuous-time proof, against their references (spec §11).
#include "mm/collision.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "mm/collision_sets.hpp"
#include "mm/footprint.hpp"
#include "mm/forecast.hpp"
#include "mm/maneuver.hpp"
#include "mm/planner.hpp"
#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

/// The obstacles of `in` as the planner estimates them, each with its own forecast time
/// 0.125 s × `forecast(rng)`.
std::pair<std::vector<forecast_obstacle>, std::vector<double>> forecast_randomly(
    const plan_input& in, std::mt19937_64& rng, std::uniform_int_distribution<int>& forecast) {
  std::pair<std::vector<forecast_obstacle>, std::vector<double>> scene;
  for (const obstacle_track& track : in.obstacles) {
    scene.first.push_back({estimate_motion(track, in.config.history_window, in.time), track.shape});
    scene.second.push_back(0.125 * forecast(rng));
  }
  return scene;
}

TEST(collision, time_to_collision_is_never_after_a_contact_of_its_reference_and_always_at_one) {
  // The reference scans the window every 10⁻⁴ s: the conservative advancement never passes an
  // overlap it sees, and where it stops the two are within L × 10⁻⁴ m (they touch, or graze).
  std::mt19937_64 rng(testing::property_seed() + 29);
  const std::size_t count = testing::property_count(100);
  std::uniform_real_distribution<double> acceleration(-7.0, 3.0);
  std::uniform_real_distribution<double> curvature(-0.1, 0.1);
  std::size_t collisions = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {3, trial % 2 == 1});
    const maneuver nominal{trial % 3 == 0 ? 0.0 : acceleration(rng), trial % 4 == 0 ? 0.0 : curvature(rng)};
    const collision_window window{in.config.displacement_horizon, in.config.collision_window,
                                  trial % 5 == 0 ? 0.02 : 0.05, trial % 3 == 1 ? 0.4 : 0.0};
    for (const obstacle_track& track : in.obstacles) {
      const forecast_obstacle obstacle{estimate_motion(track, in.config.history_window, in.time), track.shape};
      const double fast = time_to_collision(in.ego, nominal, obstacle, window);
      const double reference = time_to_collision_reference(in.ego, nominal, obstacle, window);
      const std::string what = "trial " + std::to_string(trial) + " obstacle " + std::to_string(track.id) +
                               " nominal (" + std::to_string(nominal.acceleration) + ", " +
                               std::to_string(nominal.curvature) + ")\n" + testing::describe(in);
      ASSERT_LE(fast, reference) << what;
      if (fast != no_collision) {
        const pose e = maneuver_pose(in.ego.pose, in.ego.speed, nominal, fast, window.horizon, in.ego.limits.speed_cap);
        const pose o = forecast_pose(obstacle.motion, window.duration, fast);
        const double clearance = signed_distance(place(in.ego.shape, e), place(obstacle.shape, o)) - window.margin;
        const double rate = largest_point_speed(in.ego, nominal, window.horizon) + largest_point_speed(obstacle);
        ASSERT_LE(clearance, rate * time_to_collision_resolution) << what;
      }
      collisions += reference != no_collision ? 1 : 0;
    }
  }
  EXPECT_GT(collisions, count / 4) << "the random scenes must collide often for this test to mean anything";
}

TEST(collision, first_collision_time_equals_its_reference_bit_for_bit_on_random_scenes) {
  // Every obstacle of a random scene at once, each with its own forecast time, random maneuvers.
  std::mt19937_64 rng(testing::property_seed() + 31);
  const std::size_t count = testing::property_count(200);
  std::uniform_real_distribution<double> acceleration(-7.0, 3.0);
  std::uniform_real_distribution<double> curvature(-0.15, 0.15);
  std::uniform_int_distribution<int> forecast(0, 16);
  std::size_t collisions = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {1 + trial % 3, trial % 2 == 1});
    const collision_window window{in.config.displacement_horizon, in.config.collision_window,
                                  trial % 5 == 0 ? 0.02 : 0.05, trial % 3 == 1 ? 0.4 : 0.0};
    const auto [obstacles, taus] = forecast_randomly(in, rng, forecast);
    std::vector<maneuver> maneuvers;
    for (int m = 0; m < 8; ++m) maneuvers.push_back({m % 3 == 0 ? 0.0 : acceleration(rng), m % 4 == 0 ? 0.0 : curvature(rng)});
    const std::vector<double> all = first_collision_times(in.ego, maneuvers, obstacles, taus, window);
    ASSERT_EQ(all.size(), maneuvers.size());
    for (std::size_t m = 0; m < maneuvers.size(); ++m) {
      const maneuver& u = maneuvers[m];
      const double fast = first_collision_time(in.ego, u, obstacles, taus, window);
      const double reference = first_collision_time_reference(in.ego, u, obstacles, taus, window);
      ASSERT_EQ(fast, reference) << "trial " << trial << " maneuver (" << u.acceleration << ", " << u.curvature
                                 << ")\n" << testing::describe(in);
      ASSERT_EQ(all[m], reference) << "trial " << trial << " maneuver " << m << " of the batch";
      collisions += reference != no_collision ? 1 : 0;
    }
  }
  EXPECT_GT(collisions, count) << "the random maneuvers must collide often for this test to mean anything";
}

TEST(collision, verified_collision_free_equals_its_reference_on_random_scenes) {
  // Every obstacle of a random scene at once, each with its own forecast time; random maneuvers,
  // margins and proof resolutions, so that proofs succeed, fail on a contact and fail on a short step.
  std::mt19937_64 rng(testing::property_seed() + 37);
  const std::size_t count = testing::property_count(200);
  std::uniform_real_distribution<double> acceleration(-7.0, 3.0);
  std::uniform_real_distribution<double> curvature(-0.15, 0.15);
  std::uniform_int_distribution<int> forecast(0, 16);
  std::size_t proven = 0;
  std::size_t refused = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {1 + trial % 4, trial % 2 == 1});
    const collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05,
                                  trial % 3 == 1 ? 0.4 : 0.0};
    const double resolution = trial % 4 == 0 ? 0.02 : 1e-3;
    const proof_steps stepping = trial % 5 < 2 ? proof_steps::translation_bound : proof_steps::speed_bound;
    const auto [obstacles, taus] = forecast_randomly(in, rng, forecast);
    for (int m = 0; m < 8; ++m) {
      const maneuver u{m % 3 == 0 ? 0.0 : acceleration(rng), m % 4 == 0 ? 0.0 : curvature(rng)};
      const bool reference =
          verified_collision_free_reference(in.ego, u, obstacles, taus, window, resolution, stepping);
      ASSERT_EQ(verified_collision_free(in.ego, u, obstacles, taus, window, resolution, stepping), reference)
          << "seed " << testing::property_seed() << ", trial " << trial << ", maneuver (" << u.acceleration << ", "
          << u.curvature << "), resolution " << resolution << ", translation bound "
          << (stepping == proof_steps::translation_bound) << "\n"
          << testing::describe(in);
      (reference ? proven : refused) += 1;
    }
  }
  EXPECT_GT(proven, count) << "the random maneuvers must often be proven free for this test to mean anything";
  EXPECT_GT(refused, count) << "and often not";
}

TEST(collision, what_the_translation_bound_proves_keeps_the_margin_at_every_millisecond) {
  // The proof with the translation bound on random scenes, margins and maneuvers, at a coarse
  // resolution (20 ms) where the speed bound leaves much unproven: whatever it proves keeps more
  // than the margin from every obstacle at every millisecond of the window; it proves everything the
  // speed bound does, and more.
  std::mt19937_64 rng(testing::property_seed() + 41);
  const std::size_t count = testing::property_count(150);
  std::uniform_real_distribution<double> acceleration(-7.0, 3.0);
  std::uniform_real_distribution<double> curvature(-0.15, 0.15);
  std::uniform_int_distribution<int> forecast(0, 16);
  std::size_t only_by_translation = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {1 + trial % 3, trial % 2 == 1});
    const collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05,
                                  trial % 3 == 1 ? 0.4 : 0.0};
    const auto [obstacles, taus] = forecast_randomly(in, rng, forecast);
    for (int m = 0; m < 8; ++m) {
      const maneuver u{m % 3 == 0 ? 0.0 : acceleration(rng), m % 4 == 0 ? 0.0 : curvature(rng)};
      const bool by_speed = verified_collision_free(in.ego, u, obstacles, taus, window, 0.02, proof_steps::speed_bound);
      const bool by_translation =
          verified_collision_free(in.ego, u, obstacles, taus, window, 0.02, proof_steps::translation_bound);
      const std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " +
                                std::to_string(trial) + ", maneuver (" + std::to_string(u.acceleration) + ", " +
                                std::to_string(u.curvature) + ")\n" + testing::describe(in);
      if (by_speed) {
        ASSERT_TRUE(by_translation) << input;
      }
      if (!by_translation) continue;
      only_by_translation += by_speed ? 0 : 1;
      for (int k = 0; k <= 3000; ++k) {
        const double t = std::min(window.duration, 1e-3 * k);
        const placed_footprint e =
            place(in.ego.shape, maneuver_pose(in.ego.pose, in.ego.speed, u, t, window.horizon, in.ego.limits.speed_cap));
        for (std::size_t j = 0; j < obstacles.size(); ++j) {
          const double clearance =
              signed_distance(e, place(obstacles[j].shape, forecast_pose(obstacles[j].motion, taus[j], t))) -
              window.margin;
          ASSERT_GT(clearance, 0.0) << "obstacle " << j << " at t = " << t << " s, " << input;
        }
      }
    }
  }
  EXPECT_GT(only_by_translation, count / 10) << "the translation bound must often prove what the speed bound does not";
}

}  // namespace
}  // namespace mm
