#include "mm/maneuverability.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <random>

namespace mm {
namespace {

TEST(maneuverability, positive_fraction_of_a_straight_boundary_is_exact) {
  // Clearance c(x, y) = x − 0.3: positive on 70 % of the square.
  EXPECT_NEAR(positive_fraction(-0.3, 0.7, -0.3, 0.7), 0.7, 1e-12);
  // c = 0.2 + x − y: negative on the triangle {y > x + 0.2} with legs 0.8, area 0.32.
  EXPECT_NEAR(positive_fraction(0.2, 1.2, -0.8, 0.2), 1.0 - 0.32, 1e-12);
  EXPECT_EQ(positive_fraction(1.0, 2.0, 3.0, 0.5), 1.0);
  EXPECT_EQ(positive_fraction(-1.0, -2.0, 0.0, -0.5), 0.0);
  EXPECT_NEAR(positive_fraction(-1.0, 3.0), 0.75, 1e-12);
  EXPECT_NEAR(positive_fraction(2.0, -2.0), 0.5, 1e-12);
}

TEST(maneuverability, positive_fraction_resolves_saddles_by_the_centre_value) {
  // Positive on the (0,0)–(1,1) diagonal, negative on the other: the centre decides.
  const double connected = positive_fraction(1.0, -0.2, -0.2, 1.0);  // centre 0.4 > 0
  const double split = positive_fraction(0.2, -1.0, -1.0, 0.2);      // centre −0.4 < 0
  EXPECT_GT(connected, 0.5);
  EXPECT_LT(split, 0.5);
  // Split: two corner triangles with legs 0.2/1.2 each.
  EXPECT_NEAR(split, 2.0 * 0.5 * (0.2 / 1.2) * (0.2 / 1.2), 1e-12);
  EXPECT_NEAR(connected, 1.0 - 2.0 * 0.5 * (0.2 / 1.2) * (0.2 / 1.2), 1e-12);
}

TEST(maneuverability, positive_fraction_is_symmetric_under_reflections_of_the_square) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double a = value(rng), b = value(rng), c = value(rng), d = value(rng);
    const double f = positive_fraction(a, b, c, d);
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    EXPECT_NEAR(f, positive_fraction(b, a, d, c), 1e-12);  // x ↦ 1 − x
    EXPECT_NEAR(f, positive_fraction(c, d, a, b), 1e-12);  // y ↦ 1 − y
    EXPECT_NEAR(f, positive_fraction(a, c, b, d), 1e-12);  // x ↔ y
    if (a != 0.0 && b != 0.0 && c != 0.0 && d != 0.0 && (a + b + c + d) != 0.0) {
      EXPECT_NEAR(f + positive_fraction(-a, -b, -c, -d), 1.0, 1e-12) << "complement";
    }
  }
}

/// Clearances of a displacement set's nodes from a function of (a, κ).
template <class Clearance>
std::vector<double> clearance_of(const displacement_set& set, Clearance c) {
  std::vector<double> values;
  for (const displacement_sample& s : set.samples) values.push_back(c(s.u));
  return values;
}

TEST(maneuverability, two_obstacles_leave_the_corridor_between_their_collision_sets_safe) {
  // Obstacle 1 collides where x < 0.3, obstacle 2 where x > 0.8 (both clearances linear in x). Every
  // corner collides with one of them, so the minimum of the two is ≤ 0 at every corner and its
  // interpolant sees no room; each interpolated on its own leaves 0.3 < x < 0.8.
  const std::array<cell_corners, 2> two{cell_corners{-0.3, 0.7, 0.7, -0.3}, cell_corners{0.8, -0.2, -0.2, 0.8}};
  EXPECT_NEAR(safe_fraction(two), 0.5, 1e-12);
  EXPECT_EQ(positive_fraction(-0.3, -0.2, -0.3, -0.2), 0.0);  // the minimum of the two
}

TEST(maneuverability, two_obstacles_cutting_different_corners_leave_what_neither_cuts) {
  // Obstacle 1: x + y < 0.5 (a triangle of 1/8); obstacle 2: y > 0.75 (a strip of 1/4).
  const std::array<cell_corners, 2> two{cell_corners{-0.5, 0.5, 1.5, 0.5}, cell_corners{0.75, 0.75, -0.25, -0.25}};
  EXPECT_NEAR(safe_fraction(two), 1.0 - 0.125 - 0.25, 1e-12);
  // An obstacle safe at every corner changes nothing; one unsafe at every corner leaves nothing.
  const std::array<cell_corners, 2> with_safe{two[0], cell_corners{1.0, 2.0, 3.0, 4.0}};
  EXPECT_EQ(safe_fraction(with_safe), safe_fraction(std::span(two).first(1)));
  const std::array<cell_corners, 3> with_covering{two[0], two[1], cell_corners{-1.0, -2.0, 0.0, -0.5}};
  EXPECT_EQ(safe_fraction(with_covering), 0.0);
  // Along one column: x < 0.25 unsafe for one, x > 0.5 for the other.
  const std::array<std::array<double, 2>, 2> ends{std::array<double, 2>{-0.25, 0.75}, std::array<double, 2>{0.5, -0.5}};
  EXPECT_NEAR(safe_fraction(std::span<const std::array<double, 2>>(ends)), 0.25, 1e-12);
}

TEST(maneuverability, a_cell_cut_by_many_obstacles_keeps_the_polygon_they_all_leave) {
  // n planar clearances c = r − (x − ½, y − ½)·(cos φ, sin φ), φ = 2πj/n: each one's safe region is
  // the half-plane on the centre's side of a tangent to the circle of radius r about the centre, and
  // together they leave the regular n-gon circumscribed about it, of area n r² tan(π/n). Sixteen
  // cuts give a polygon of sixteen vertices (more than the twelve a cell keeps in place).
  constexpr double r = 0.4;
  for (const int n : {3, 8, 12, 13, 16, 40}) {
    std::vector<cell_corners> corners;
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / n;
      const auto at = [&](double x, double y) { return r - ((x - 0.5) * std::cos(phi) + (y - 0.5) * std::sin(phi)); };
      corners.push_back({at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
    }
    const double polygon = n * r * r * std::tan(std::numbers::pi / n);
    // For n = 3 the triangle reaches past the cell: the cell clips it.
    if (n == 3) {
      EXPECT_LT(safe_fraction(corners), polygon) << n;
      continue;
    }
    EXPECT_NEAR(safe_fraction(corners), polygon, 1e-12) << n << " cuts";
  }
}

TEST(maneuverability, one_obstacle_s_safe_fraction_is_its_positive_fraction) {
  const cell_corners saddle{0.2, -1.0, 0.2, -1.0};
  EXPECT_EQ(safe_fraction(std::span(&saddle, 1)), positive_fraction(0.2, -1.0, -1.0, 0.2));
  const cell_corners corner{-0.4, 0.6, 1.1, 0.3};
  EXPECT_EQ(safe_fraction(std::span(&corner, 1)), positive_fraction(-0.4, 0.6, 0.3, 1.1));
}

TEST(maneuverability, interpolated_index_places_a_boundary_between_nodes_where_counting_cannot) {
  ego_state ego;
  ego.speed = 10.0;
  const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, {11, 15});
  const displacement_set& brake = samples.brake;
  // Collision for a > −2.35 m/s²: the exact share is the area of the displacements of a ≤ −2.35.
  const auto c = clearance_of(brake, [](const maneuver& u) { return -2.35 - u.acceleration; });
  const double s_lo = travelled_distance(10.0, -7.0, 1.0, 30.0);
  const double s_cut = travelled_distance(10.0, -2.35, 1.0, 30.0);
  const double s_hi = 10.0;
  // Area between two fronts s0 < s1 of the sector: ∫∫ dA; the κ range is symmetric.
  const auto area = [&](double s0, double s1) {
    double sum = 0.0;
    constexpr int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double kappa = -brake.max_curvature + (i + 0.5) * 2.0 * brake.max_curvature / n;
      sum += area_element_primitive(s1, kappa) - area_element_primitive(s0, kappa);
    }
    return sum * 2.0 * brake.max_curvature / n;
  };
  const double exact = area(s_lo, s_cut) / area(s_lo, s_hi);
  const double interpolated = maneuverability_index(brake, c);
  sample_mask colliding(samples.size());
  for (std::size_t m = 0; m < brake.samples.size(); ++m) {
    if (c[m] <= 0.0) colliding.set(m);
  }
  const double counted = maneuverability_index(samples, family::brake, colliding);
  EXPECT_NEAR(interpolated, exact, 0.004);
  EXPECT_GT(std::abs(counted - exact), 0.01) << "node counting puts the boundary half-way at −2.1 or −2.8";
}

TEST(maneuverability, the_sign_index_is_the_interpolated_index_of_plus_and_minus_one_values) {
  ego_state ego;
  ego.speed = 8.0;
  const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, {9, 13});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> c(samples.brake.samples.size());
    // Blobs of one sign as well as noise: some sets have few sign changes, some many.
    const double threshold = value(rng);
    for (std::size_t m = 0; m < c.size(); ++m) c[m] = trial % 2 == 0 ? value(rng) : threshold - static_cast<double>(m % 13) * 0.4;
    std::vector<double> unit(c.size());
    for (std::size_t m = 0; m < c.size(); ++m) unit[m] = c[m] > 0.0 ? 2.0 : -2.0;
    ASSERT_EQ(sign_index(samples.brake, c), maneuverability_index(samples.brake, unit)) << "trial " << trial;
  }
  // A boundary through a row of nodes' middles: the half-way rule, not the interpolation.
  const auto c = clearance_of(samples.brake, [](const maneuver& u) { return -2.35 - u.acceleration; });
  EXPECT_NE(sign_index(samples.brake, c), maneuverability_index(samples.brake, c));
}

TEST(maneuverability, degenerate_set_counts_its_safe_nodes) {
  ego_state stopped;
  const maneuver_samples samples = sample_maneuvers(stopped, 0.0, 1.0, {5, 3});
  ASSERT_TRUE(samples.brake.degenerate);
  EXPECT_EQ(maneuverability_index(samples.brake, std::vector<double>(15, 0.4)), 1.0);
  EXPECT_EQ(maneuverability_index(samples.brake, std::vector<double>(15, -0.4)), 0.0);
  sample_mask none(samples.size());
  EXPECT_EQ(maneuverability_indices(samples, none).brake, 1.0);
}

TEST(maneuverability, counting_index_is_the_safe_share_of_the_node_weights) {
  ego_state ego;
  ego.speed = 8.0;
  const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, {5, 5});
  sample_mask colliding(samples.size());
  const index_range accel = samples.grid(family::accelerate);
  double unsafe = 0.0;
  for (std::size_t m = accel.begin; m < accel.end; m += 3) {
    colliding.set(m);
    unsafe += samples.area_weights[m];
  }
  const maneuverability_pair mi = maneuverability_indices(samples, colliding);
  EXPECT_EQ(mi.brake, 1.0);
  EXPECT_NEAR(mi.accelerate, 1.0 - unsafe / samples.total_weight(family::accelerate), 1e-12);
}

}  // namespace
}  // namespace mm
