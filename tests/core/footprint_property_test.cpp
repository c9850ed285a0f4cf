#include "mm/footprint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

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

TEST(footprint_property, the_face_separation_of_each_of_many_rectangles_equals_face_separation_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 7);
  std::uniform_real_distribution<double> coordinate(-6.0, 6.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  std::uniform_real_distribution<double> size(0.0, 3.0);
  std::uniform_int_distribution<std::size_t> length(0, 17);
  const std::size_t count = testing::property_count(5000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const std::size_t n = length(rng);
    const vec2 half{size(rng), size(rng)};
    const double heading = angle(rng);
    const placed_rectangle b{{coordinate(rng), coordinate(rng)}, unit_vector(heading), size(rng), size(rng)};
    std::vector<double> x(n), y(n), c(n), s(n), out(n);
    for (std::size_t i = 0; i < n; ++i) {
      // Some parallel to b, some touching it along a face, some on its centre.
      const int kind = static_cast<int>(rng() % 4);
      const vec2 axis = kind == 1 ? b.axis : unit_vector(angle(rng));
      vec2 centre{coordinate(rng), coordinate(rng)};
      if (kind == 2) centre = b.centre + (b.half_length + half.x) * b.axis;
      if (kind == 3) centre = b.centre;
      x[i] = centre.x;
      y[i] = centre.y;
      c[i] = axis.x;
      s[i] = axis.y;
    }
    face_separation_of_each(n, x.data(), y.data(), c.data(), s.data(), half, b, out.data());
    for (std::size_t i = 0; i < n; ++i) {
      const double single = face_separation(placed_rectangle{{x[i], y[i]}, {c[i], s[i]}, half.x, half.y}, b);
      ASSERT_EQ(std::signbit(out[i]), std::signbit(single));
      ASSERT_EQ(out[i], single) << "trial " << trial << ", rectangle " << i << " of " << n << " at (" << x[i] << ", "
                                << y[i] << ") axis (" << c[i] << ", " << s[i] << ") half sides " << half.x << " x "
                                << half.y << ", b at (" << b.centre.x << ", " << b.centre.y << ") axis (" << b.axis.x
                                << ", " << b.axis.y << ") half sides " << b.half_length << " x " << b.half_width;
    }
  }
}

TEST(footprint_property, corner_distance_equals_its_corner_by_corner_reference_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 6);
  std::uniform_real_distribution<double> coordinate(-6.0, 6.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  std::uniform_real_distribution<double> size(0.0, 5.0);
  std::uniform_int_distribution<int> special(0, 5);
  const std::size_t count = testing::property_count(20000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    // Some pairs parallel or perpendicular, some with a zero side, some touching along a face:
    // where corners tie and distances are zero.
    const double heading_a = angle(rng);
    double heading_b = angle(rng);
    const int kind = special(rng);
    if (kind == 1) heading_b = heading_a;
    if (kind == 2) heading_b = heading_a + pi / 2.0;
    const placed_rectangle a{{coordinate(rng), coordinate(rng)}, unit_vector(heading_a), size(rng) / 2.0,
                             kind == 3 ? 0.0 : size(rng) / 2.0};
    placed_rectangle b{{coordinate(rng), coordinate(rng)}, unit_vector(heading_b), size(rng) / 2.0, size(rng) / 2.0};
    if (kind == 4) b.centre = a.centre + vec2{a.half_length + b.half_length, 0.0};
    if (kind == 5) b.axis = a.axis;
    const double fast = corner_distance(a, b);
    const double reference = corner_distance_reference(a, b);
    ASSERT_EQ(std::signbit(fast), std::signbit(reference));
    ASSERT_EQ(fast, reference) << "trial " << trial << ": a at (" << a.centre.x << ", " << a.centre.y << ") axis ("
                               << a.axis.x << ", " << a.axis.y << ") half sides " << a.half_length << " x "
                               << a.half_width << ", b at (" << b.centre.x << ", " << b.centre.y << ") axis ("
                               << b.axis.x << ", " << b.axis.y << ") half sides " << b.half_length << " x "
                               << b.half_width;
  }
}

}  // namespace
}  // namespace mm
