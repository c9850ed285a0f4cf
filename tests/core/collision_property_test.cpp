// The time to collision that skips provably free sample times, against its reference (spec §11).
#include "mm/collision.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "mm/planner.hpp"
#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

TEST(collision, time_to_collision_equals_its_reference_bit_for_bit_on_random_scenes) {
  std::mt19937_64 rng(testing::property_seed() + 29);
  const std::size_t count = testing::property_count(200);
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
      ASSERT_EQ(fast, reference) << "trial " << trial << " obstacle " << track.id << " nominal (" << nominal.acceleration
                                 << ", " << nominal.curvature << ")\n"
                                 << testing::describe(in);
      collisions += reference != no_collision ? 1 : 0;
    }
  }
  EXPECT_GT(collisions, count / 4) << "the random scenes must collide often for this test to mean anything";
}

}  // namespace
}  // namespace mm
