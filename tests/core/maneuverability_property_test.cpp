#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "mm/maneuverability.hpp"
#include "property.hpp"

namespace mm {
namespace {

std::string signs_of(const sample_mask& positive) {
  std::string text;
  for (std::size_t m = 0; m < positive.size(); ++m) text += positive.test(m) ? '+' : '-';
  return text;
}

/// An ego at a random speed of 1 to 20.9 m/s (one draw of `rng`).
ego_state ego_at_random_speed(std::mt19937_64& rng) {
  ego_state ego;
  ego.speed = 1.0 + static_cast<double>(rng() % 200) / 10.0;
  return ego;
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

/// Σ_cells W · positive_fraction(corners) / Σ_cells W, cell by cell in index order (the definition
/// of the interpolated index, spec §6), with `fraction` for a cell's positive share.
template <class Fraction>
double index_cell_by_cell(const displacement_set& set, const std::vector<double>& c, Fraction&& fraction) {
  const std::size_t columns = set.curvature_count;
  double total = 0.0;
  double safe = 0.0;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    for (std::size_t ik = 0; ik + 1 < columns; ++ik) {
      const double w = set.cell_weights[ia * (columns - 1) + ik];
      const std::size_t lower = ia * columns + ik;
      total += w;
      safe += w * fraction(c[lower], c[lower + 1], c[lower + columns], c[lower + columns + 1]);
    }
  }
  return total <= 0.0 ? 1.0 : std::clamp(safe / total, 0.0, 1.0);
}

TEST(maneuverability_properties, the_indices_with_and_without_sign_bits_are_the_cell_by_cell_sums_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 32);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  const std::size_t count = testing::property_count(600);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const ego_state ego = ego_at_random_speed(rng);
    // Rows longer than a word now and then (the node-by-node path).
    const sampling_resolution resolution{2 + rng() % 20, trial % 9 == 0 ? 60 + rng() % 10 : 2 + rng() % 40};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    const displacement_set& set = trial % 2 == 0 ? samples.brake : samples.accelerate;
    std::vector<double> c(set.samples.size());
    // Noise, blobs of one sign, or safe everywhere but a few nodes.
    const double threshold = value(rng);
    for (std::size_t m = 0; m < c.size(); ++m) {
      switch (trial % 3) {
        case 0: c[m] = value(rng); break;
        case 1: c[m] = threshold - static_cast<double>(m % 13) * 0.4; break;
        default: c[m] = rng() % 25 == 0 ? -1.0 : 0.5 + value(rng) * value(rng); break;
      }
    }
    const double interpolated = index_cell_by_cell(set, c, [](double a, double b, double d, double e) {
      return positive_fraction(a, b, d, e);
    });
    const double signs = index_cell_by_cell(set, c, [](double a, double b, double d, double e) {
      const auto unit = [](double x) { return x > 0.0 ? 1.0 : -1.0; };
      return positive_fraction(unit(a), unit(b), unit(d), unit(e));
    });
    const std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " + std::to_string(trial) +
                              ", resolution " + std::to_string(resolution.accelerations) + " x " +
                              std::to_string(resolution.curvatures);
    ASSERT_EQ(maneuverability_index(set, c), interpolated) << input;
    ASSERT_EQ(sign_index(set, c), signs) << input;
    // The same with the signs given as bits of a mask, from an offset that crosses words.
    const std::size_t first = rng() % 100;
    sample_mask positive(first + c.size() + rng() % 5);
    for (std::size_t m = 0; m < c.size(); ++m) {
      if (c[m] > 0.0) positive.set(first + m);
    }
    ASSERT_EQ(maneuverability_index(set, c, positive, first), interpolated) << input << ", first " << first;
    ASSERT_EQ(sign_index(set, positive, first), signs) << input << ", first " << first;
  }
}

TEST(maneuverability_properties, the_safe_share_of_several_planar_clearances_is_the_area_where_every_one_is_positive) {
  // Clearances that are planes (c = α + βx + γy) interpolate exactly: each obstacle's safe region
  // is a half-plane, and safe_fraction must be the area where all are positive, here counted on a
  // 400 × 400 grid of points (so within about 2/400 of it).
  std::mt19937_64 rng(testing::property_seed() + 33);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  const std::size_t count = testing::property_count(300);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const std::size_t obstacles = 1 + trial % 4;
    std::vector<std::array<double, 3>> planes;
    std::vector<cell_corners> corners;
    for (std::size_t j = 0; j < obstacles; ++j) {
      const std::array<double, 3> p{0.3 * coefficient(rng), coefficient(rng), coefficient(rng)};
      const auto at = [&](double x, double y) { return p[0] + p[1] * x + p[2] * y; };
      planes.push_back(p);
      corners.push_back({at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
    }
    constexpr int n = 400;
    int inside = 0;
    for (int ix = 0; ix < n; ++ix) {
      for (int iy = 0; iy < n; ++iy) {
        const double x = (ix + 0.5) / n;
        const double y = (iy + 0.5) / n;
        bool safe = true;
        for (const auto& p : planes) safe = safe && p[0] + p[1] * x + p[2] * y > 0.0;
        inside += safe ? 1 : 0;
      }
    }
    std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " + std::to_string(trial) + ":";
    for (const auto& p : planes) input += " (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
    const double share = safe_fraction(corners);
    ASSERT_NEAR(share, static_cast<double>(inside) / (n * n), 0.006) << input;
    // The order of the obstacles does not matter.
    std::reverse(corners.begin(), corners.end());
    ASSERT_NEAR(safe_fraction(corners), share, 1e-12) << input;
  }
}

TEST(maneuverability_properties, the_index_of_a_union_is_the_one_obstacle_index_when_only_one_obstacle_collides) {
  std::mt19937_64 rng(testing::property_seed() + 34);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  const std::size_t count = testing::property_count(200);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const ego_state ego = ego_at_random_speed(rng);
    const sampling_resolution resolution{2 + rng() % 20, trial % 5 == 0 ? 1 : 2 + rng() % 30};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    const displacement_set& set = trial % 2 == 0 ? samples.brake : samples.accelerate;
    std::vector<double> colliding(set.samples.size());
    std::vector<double> clear(set.samples.size());
    for (std::size_t m = 0; m < colliding.size(); ++m) {
      colliding[m] = value(rng);
      clear[m] = 0.01 + std::abs(value(rng));
    }
    const std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " + std::to_string(trial);
    const std::array<std::span<const double>, 1> one{colliding};
    const std::array<std::span<const double>, 3> three{clear, colliding, clear};
    ASSERT_EQ(maneuverability_index_of_union(set, one), maneuverability_index(set, colliding)) << input;
    ASSERT_EQ(maneuverability_index_of_union(set, three), maneuverability_index(set, colliding)) << input;
  }
}

TEST(maneuverability_properties, the_index_of_a_union_with_sign_bits_is_the_cell_by_cell_one_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 35);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  const std::size_t count = testing::property_count(300);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const ego_state ego = ego_at_random_speed(rng);
    // Now and then one column, or rows longer than a word (the node-by-node path).
    const std::size_t curvatures = trial % 11 == 0 ? 1 : trial % 13 == 0 ? 65 + rng() % 5 : 2 + rng() % 40;
    const sampling_resolution resolution{2 + rng() % 20, curvatures};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    const displacement_set& set = trial % 2 == 0 ? samples.brake : samples.accelerate;
    const std::size_t obstacles = 1 + trial % 4;
    const std::size_t first = rng() % 100;
    std::vector<std::vector<double>> values(obstacles, std::vector<double>(set.samples.size()));
    std::vector<sample_mask> negative(obstacles, sample_mask(first + set.samples.size() + rng() % 5));
    for (std::size_t j = 0; j < obstacles; ++j) {
      // Blobs of one sign around a random centre, so that obstacles overlap and leave corridors.
      const double centre = static_cast<double>(rng() % set.samples.size());
      const double radius = 1.0 + static_cast<double>(rng() % 30);
      for (std::size_t m = 0; m < set.samples.size(); ++m) {
        const double c = std::abs(static_cast<double>(m) - centre) - radius + 0.3 * value(rng);
        values[j][m] = trial % 5 == 4 ? value(rng) : c;
        if (!(values[j][m] > 0.0)) negative[j].set(first + m);
      }
    }
    std::vector<std::span<const double>> spans(values.begin(), values.end());
    const std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " + std::to_string(trial) +
                              ", resolution " + std::to_string(resolution.accelerations) + " x " +
                              std::to_string(resolution.curvatures) + ", obstacles " + std::to_string(obstacles);
    ASSERT_EQ(maneuverability_index_of_union(set, spans, negative, first), maneuverability_index_of_union(set, spans))
        << input;
  }
}

TEST(maneuverability_properties, a_union_that_keeps_each_obstacle_s_single_shares_gives_the_cell_by_cell_index_at_every_call) {
  // The forecast-time search evaluates unions of the same obstacles' clearances many times, each
  // obstacle keeping the shares of the cells it alone touches: every union, first or again, in any
  // order, must equal the cell-by-cell index bit for bit.
  std::mt19937_64 rng(testing::property_seed() + 41);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  std::size_t kept = 0;
  const std::size_t count = testing::property_count(200);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const ego_state ego = ego_at_random_speed(rng);
    const sampling_resolution resolution{2 + rng() % 20, 2 + rng() % 40};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    const displacement_set& set = trial % 2 == 0 ? samples.brake : samples.accelerate;
    const std::size_t obstacles = 2 + trial % 3;
    const std::size_t first = rng() % 100;
    std::vector<std::vector<double>> values(obstacles, std::vector<double>(set.samples.size()));
    std::vector<sample_mask> negative(obstacles, sample_mask(first + set.samples.size()));
    for (std::size_t j = 0; j < obstacles; ++j) {
      const double centre = static_cast<double>(rng() % set.samples.size());
      const double radius = 1.0 + static_cast<double>(rng() % 30);
      for (std::size_t m = 0; m < set.samples.size(); ++m) {
        values[j][m] = std::abs(static_cast<double>(m) - centre) - radius + 0.3 * value(rng);
        if (!(values[j][m] > 0.0)) negative[j].set(first + m);
      }
    }
    std::vector<std::vector<double>> shares(
        obstacles, std::vector<double>(set.cell_weights.size(), std::numeric_limits<double>::quiet_NaN()));
    // Every union of two or more of the obstacles, twice, in a random order.
    std::vector<unsigned> unions;
    for (unsigned subset = 1; subset < (1U << obstacles); ++subset) {
      if (std::popcount(subset) >= 2) unions.insert(unions.end(), {subset, subset});
    }
    std::shuffle(unions.begin(), unions.end(), rng);
    for (const unsigned subset : unions) {
      std::vector<std::span<const double>> spans;
      std::vector<sample_mask> bits;
      std::vector<double*> kept_shares;
      for (std::size_t j = 0; j < obstacles; ++j) {
        if (((subset >> j) & 1U) == 0) continue;
        spans.emplace_back(values[j]);
        bits.push_back(negative[j]);
        kept_shares.push_back(shares[j].data());
      }
      ASSERT_EQ(maneuverability_index_of_union(set, spans, bits, first, kept_shares),
                maneuverability_index_of_union(set, spans))
          << "seed " << testing::property_seed() << ", trial " << trial << ", resolution " << resolution.accelerations
          << " x " << resolution.curvatures << ", obstacles " << obstacles << ", union " << subset;
    }
    for (const std::vector<double>& s : shares) {
      kept += static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](double x) { return !std::isnan(x); }));
    }
  }
  EXPECT_GT(kept, count) << "the unions kept some cells' shares";
}

TEST(maneuverability_properties, the_indices_with_sign_bits_equal_the_node_by_node_ones_on_degenerate_and_one_column_sets) {
  std::mt19937_64 rng(testing::property_seed() + 33);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  for (std::size_t trial = 0; trial < testing::property_count(300); ++trial) {
    ego_state ego;
    ego.speed = trial % 2 == 0 ? 0.0 : 1.0 + static_cast<double>(rng() % 100) / 10.0;  // stopped: [AS−] degenerate
    const sampling_resolution resolution{2 + rng() % 15, trial % 4 < 2 ? 1 : 2 + rng() % 20};
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, resolution, false, false);
    for (const family f : {family::brake, family::accelerate}) {
      const displacement_set& set = samples.set(f);
      std::vector<double> c(set.samples.size());
      for (double& x : c) x = value(rng);
      const std::size_t first = samples.grid(f).begin;
      sample_mask positive(samples.size());
      for (std::size_t m = 0; m < c.size(); ++m) {
        if (c[m] > 0.0) positive.set(first + m);
      }
      const std::string input = "seed " + std::to_string(testing::property_seed()) + ", trial " + std::to_string(trial) +
                                (set.degenerate ? ", degenerate" : "") + ", resolution " +
                                std::to_string(resolution.accelerations) + " x " + std::to_string(resolution.curvatures);
      ASSERT_EQ(maneuverability_index(set, c, positive, first), maneuverability_index(set, c)) << input;
      ASSERT_EQ(sign_index(set, positive, first), sign_index(set, c)) << input;
    }
  }
}

}  // namespace
}  // namespace mm
