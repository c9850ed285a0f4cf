#include "mm/footprint.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

placed_footprint car_at(double x, double y, double heading) { return place(rectangle{4.5, 1.8}, {{x, y}, heading}); }

TEST(footprint, rectangles_overlap_exactly_when_their_extents_intersect) {
  const placed_footprint a = car_at(0.0, 0.0, 0.0);
  EXPECT_TRUE(overlaps(a, car_at(4.4, 0.0, 0.0)));
  EXPECT_FALSE(overlaps(a, car_at(4.6, 0.0, 0.0)));
  EXPECT_FALSE(overlaps(a, car_at(4.5, 0.0, 0.0))) << "touching is not overlap";
  EXPECT_TRUE(overlaps(a, car_at(0.0, 1.7, 0.0)));
  EXPECT_FALSE(overlaps(a, car_at(0.0, 1.9, 0.0)));
}

TEST(footprint, separating_axis_test_finds_the_gap_of_rotated_rectangles) {
  // A square rotated by 45° reaches √2 along x.
  const placed_footprint square = place(rectangle{2.0, 2.0}, {{0.0, 0.0}, pi / 4.0});
  const double corner = std::sqrt(2.0);
  EXPECT_TRUE(overlaps(square, place(rectangle{2.0, 2.0}, {{corner + 0.99, 0.0}, 0.0})));
  EXPECT_FALSE(overlaps(square, place(rectangle{2.0, 2.0}, {{corner + 1.01, 0.0}, 0.0})));
  // The axis-aligned bounding boxes of these overlap, the rectangles do not.
  const placed_footprint a = car_at(0.0, 0.0, pi / 4.0);
  const placed_footprint b = car_at(2.2, -2.2, pi / 4.0);
  EXPECT_FALSE(overlaps(a, b));
  EXPECT_NEAR(gap_distance(a, b), std::hypot(2.2, 2.2) - 1.8, 1e-12);
}

TEST(footprint, disc_overlap_and_gap_distance_match_closed_forms) {
  const placed_footprint walker = place(disc{0.35}, {{0.0, 0.0}, 0.0});
  EXPECT_TRUE(overlaps(walker, place(disc{0.35}, {{0.69, 0.0}, 1.0})));
  EXPECT_FALSE(overlaps(walker, place(disc{0.35}, {{0.71, 0.0}, 1.0})));
  EXPECT_NEAR(gap_distance(walker, place(disc{0.35}, {{3.0, 4.0}, 0.0})), 5.0 - 0.7, 1e-12);
  // Disc against the long side, the short side and a corner of a car.
  const placed_footprint car = car_at(0.0, 0.0, 0.0);
  EXPECT_NEAR(gap_distance(car, place(disc{0.35}, {{0.0, 3.0}, 0.0})), 3.0 - 0.9 - 0.35, 1e-12);
  EXPECT_NEAR(gap_distance(car, place(disc{0.35}, {{5.0, 0.0}, 0.0})), 5.0 - 2.25 - 0.35, 1e-12);
  EXPECT_NEAR(gap_distance(car, place(disc{0.35}, {{2.25 + 3.0, 0.9 + 4.0}, 0.0})), 5.0 - 0.35, 1e-12);
  EXPECT_TRUE(overlaps(car, place(disc{0.35}, {{2.5, 0.0}, 0.0})));
  EXPECT_TRUE(overlaps(car, place(disc{0.35}, {{0.0, 0.0}, 0.0}))) << "disc inside the car";
}

TEST(footprint, margin_inflates_the_obstacle_by_exactly_its_width) {
  const placed_footprint a = car_at(0.0, 0.0, 0.0);
  const placed_footprint b = car_at(5.0, 0.0, 0.0);  // 0.5 m gap
  EXPECT_NEAR(gap_distance(a, b), 0.5, 1e-12);
  EXPECT_FALSE(overlaps(a, b, 0.49));
  EXPECT_TRUE(overlaps(a, b, 0.51));
}

TEST(footprint, polygon_overlap_agrees_with_point_sampling) {
  const convex_polygon pentagon{{{2.0, 0.0}, {0.5, 1.5}, {-1.5, 1.0}, {-1.5, -1.0}, {0.5, -1.5}}};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  int disagreements = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const placed_footprint p = place(pentagon, {{0.0, 0.0}, angle(rng)});
    const placed_footprint walker = place(disc{0.3}, {{coordinate(rng), coordinate(rng)}, 0.0});
    // Brute force: the disc overlaps the polygon iff its centre lies inside or within 0.3 m of an edge.
    const vec2 c = walker.vertices[0];
    bool inside = true;
    double nearest = 1e9;
    for (std::size_t i = 0; i < p.vertex_count; ++i) {
      const vec2 a = p.vertices[i];
      const vec2 b = p.vertices[(i + 1) % p.vertex_count];
      inside = inside && cross(b - a, c - a) > 0.0;
      for (int k = 0; k <= 2000; ++k) nearest = std::min(nearest, norm(a + (k / 2000.0) * (b - a) - c));
    }
    const bool expected = inside || nearest < 0.3;
    if (std::abs(nearest - 0.3) < 1e-3) continue;  // too close to call by sampling
    if (overlaps(p, walker) != expected) ++disagreements;
    if (!expected) {
      EXPECT_NEAR(gap_distance(p, walker), nearest - 0.3, 1e-5);
    }
  }
  EXPECT_EQ(disagreements, 0);
}

TEST(footprint, bounding_radius_and_smallest_dimension_are_those_of_the_shape) {
  EXPECT_NEAR(bounding_radius(rectangle{4.5, 1.8}), std::hypot(2.25, 0.9), 1e-12);
  EXPECT_DOUBLE_EQ(smallest_dimension(rectangle{4.5, 1.8}), 1.8);
  EXPECT_DOUBLE_EQ(bounding_radius(disc{0.35}), 0.35);
  EXPECT_DOUBLE_EQ(smallest_dimension(disc{0.35}), 0.7);
  const convex_polygon square{{{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}}};
  EXPECT_NEAR(bounding_radius(square), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(smallest_dimension(square), 2.0, 1e-12);
}

TEST(footprint, invalid_shapes_are_reported_with_the_reason) {
  EXPECT_FALSE(footprint_error(rectangle{4.5, 1.8}));
  EXPECT_FALSE(footprint_error(convex_polygon{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}}));
  EXPECT_FALSE(footprint_error(convex_polygon{{{0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}}})) << "clockwise is fine";
  const auto width = footprint_error(rectangle{4.5, 0.0});
  ASSERT_TRUE(width);
  EXPECT_NE(width->find("width"), std::string::npos) << *width;
  EXPECT_TRUE(footprint_error(rectangle{std::nan(""), 1.8}));
  EXPECT_TRUE(footprint_error(disc{-0.1}));
  const auto few = footprint_error(convex_polygon{{{0.0, 0.0}, {1.0, 0.0}}});
  ASSERT_TRUE(few);
  EXPECT_NE(few->find("3 to 16 vertices"), std::string::npos) << *few;
  const auto dent = footprint_error(convex_polygon{{{0.0, 0.0}, {2.0, 0.0}, {1.0, 0.5}, {2.0, 2.0}, {0.0, 2.0}}});
  ASSERT_TRUE(dent);
  EXPECT_NE(dent->find("not convex"), std::string::npos) << *dent;
  const auto star = footprint_error(
      convex_polygon{{{1.0, 0.0}, {-0.81, 0.59}, {0.31, -0.95}, {0.31, 0.95}, {-0.81, -0.59}}});
  ASSERT_TRUE(star);
  EXPECT_NE(star->find("self-intersecting"), std::string::npos) << *star;
  EXPECT_TRUE(footprint_error(convex_polygon{{{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}}}));
}

}  // namespace
}  // namespace mm
