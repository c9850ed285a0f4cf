#include <gtest/gtest.h>

#include <random>
#include <string>

#include "mm/maneuverability.hpp"
#include "property.hpp"

namespace mm {
namespace {

std::string signs_of(const sample_mask& positive) {
  std::string text;
  for (std::size_t m = 0; m < positive.size(); ++m) text += positive.test(m) ? '+' : '-';
  return text;
}

TEST(maneuverability_properties, read_nodes_by_rows_of_bits_are_the_reference_s_node_by_node) {
  std::mt19937_64 rng(testing::property_seed() + 31);
  const std::size_t count = testing::property_count(600);
  for (std::size_t trial = 0; trial < count; ++trial) {
    ego_state ego;
    // Now and then a stopped ego (degenerate sets, which read nothing) and rows longer than a word.
    ego.speed = trial % 11 == 0 ? 0.0 : 1.0 + static_cast<double>(rng() % 200) / 10.0;
    const sampling_resolution resolution{2 + rng() % 16, trial % 7 == 0 ? 60 + rng() % 10 : 1 + rng() % 30};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    sample_mask positive(samples.size());
    // Blobs of one sign (a threshold on the index) as well as noise.
    const std::size_t cut = rng() % (samples.size() + 1);
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const bool p = trial % 2 == 0 ? rng() % 2 == 0 : (m < cut) != (m % 17 == 3);
      if (p) positive.set(m);
    }
    sample_mask read(3);
    read_nodes(samples, positive, read);
    ASSERT_EQ(read, read_nodes_reference(samples, positive))
        << "seed " << testing::property_seed() << ", trial " << trial << ", speed " << ego.speed << ", resolution "
        << resolution.accelerations << " x " << resolution.curvatures << ", signs " << signs_of(positive);
  }
}

TEST(maneuverability_properties, a_grid_of_one_sign_reads_no_node_and_one_changed_node_reads_its_neighbours) {
  ego_state ego;
  ego.speed = 8.0;
  const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, {5, 7});
  sample_mask positive(samples.size());
  for (std::size_t m = 0; m < samples.size(); ++m) positive.set(m);
  sample_mask read;
  read_nodes(samples, positive, read);
  EXPECT_TRUE(read.none());
  // Node (row 2, column 3) of the braking grid: itself and its four neighbours are read.
  const std::size_t first = samples.grid(family::brake).begin;
  const std::size_t node = first + 2 * 7 + 3;
  positive.reset(node);
  read_nodes(samples, positive, read);
  EXPECT_EQ(read.count(), 5U);
  for (const std::size_t m : {node, node - 1, node + 1, node - 7, node + 7}) EXPECT_TRUE(read.test(m)) << m;
}

}  // namespace
}  // namespace mm
