#include "mm/footprint.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <string>

#include "property.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

TEST(footprint_property, rectangle_closed_forms_equal_the_placed_footprints_and_the_general_polygon_distance) {
  std::mt19937_64 rng(testing::property_seed() + 5);
  std::uniform_real_distribution<double> coordinate(-6.0, 6.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  std::uniform_real_distribution<double> size(0.3, 5.0);
  const std::size_t count = testing::property_count(4000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const rectangle ra{size(rng), size(rng)};
    const rectangle rb{size(rng), size(rng)};
    const pose pa{{coordinate(rng), coordinate(rng)}, angle(rng)};
    const pose pb{{coordinate(rng), coordinate(rng)}, angle(rng)};
    const placed_footprint a = place(ra, pa);
    const placed_footprint b = place(rb, pb);
    const placed_rectangle qa{a.centre, a.axis, ra.length / 2.0, ra.width / 2.0};
    const placed_rectangle qb{b.centre, b.axis, rb.length / 2.0, rb.width / 2.0};
    const auto as_polygon = [](const rectangle& r) {
      const double x = r.length / 2.0;
      const double y = r.width / 2.0;
      return convex_polygon{{{x, y}, {-x, y}, {-x, -y}, {x, -y}}};
    };
    const double closed = signed_distance(qa, qb);
    const double general = signed_distance(place(as_polygon(ra), pa), place(as_polygon(rb), pb));
    const std::string input = "trial " + std::to_string(trial) + ": a " + std::to_string(ra.length) + " x " +
                              std::to_string(ra.width) + " at (" + std::to_string(pa.position.x) + ", " +
                              std::to_string(pa.position.y) + ", " + std::to_string(pa.heading) + "), b " +
                              std::to_string(rb.length) + " x " + std::to_string(rb.width) + " at (" +
                              std::to_string(pb.position.x) + ", " + std::to_string(pb.position.y) + ", " +
                              std::to_string(pb.heading) + ")";
    ASSERT_EQ(closed, signed_distance(a, b)) << input;
    ASSERT_NEAR(closed, general, 1e-9) << input;
    // b's centre as a disc of radius b.width / 2.
    const double radius = rb.width / 2.0;
    const double disc_closed = signed_distance(qa, pb.position, radius);
    ASSERT_EQ(disc_closed, signed_distance(a, place(disc{radius}, pb))) << input;
    ASSERT_EQ(disc_closed, signed_distance(place(disc{radius}, pb), a)) << input;
    ASSERT_NEAR(disc_closed, signed_distance(place(as_polygon(ra), pa), place(disc{radius}, pb)), 1e-9) << input;
    const double separation = face_separation(qa, qb);
    ASSERT_LE(separation, closed + 1e-12) << input;
    if (closed <= 0.0) {
      ASSERT_EQ(separation, closed) << input;
    } else {
      ASSERT_EQ(corner_distance(qa, qb), closed) << input;
    }
  }
}

}  // namespace
}  // namespace mm
