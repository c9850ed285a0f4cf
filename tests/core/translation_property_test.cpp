// The closed forms of a translation (mm/translation.hpp) against dense sampling of the signed
// distance along it, and the rectangle forms against the general one, on random pairs.
#include "mm/translation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "property.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

/// A random pair: rectangle `a` moving relative to rectangle `b`, placed near each other so that
/// about half the translations make them overlap.
struct random_pair {
  placed_rectangle a;
  placed_rectangle b;
  translation motion;
  std::string describe() const {
    std::ostringstream out;
    out.precision(17);
    out << "a centre (" << a.centre.x << ", " << a.centre.y << ") axis (" << a.axis.x << ", " << a.axis.y << ") half "
        << a.half_length << " x " << a.half_width << "; b centre (" << b.centre.x << ", " << b.centre.y << ") axis ("
        << b.axis.x << ", " << b.axis.y << ") half " << b.half_length << " x " << b.half_width << "; velocity ("
        << motion.velocity.x << ", " << motion.velocity.y << ") duration " << motion.duration;
    return out.str();
  }
};

random_pair draw(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  std::uniform_real_distribution<double> half(0.2, 2.5);
  random_pair p;
  p.b = {{0.0, 0.0}, unit_vector(angle(rng)), half(rng), half(rng)};
  // a starts on a circle around b and moves roughly towards it (sometimes away, sometimes still).
  const double start_angle = angle(rng);
  const double distance = 2.0 + 18.0 * unit(rng);
  p.a = {distance * unit_vector(start_angle), unit_vector(angle(rng)), half(rng), half(rng)};
  const double speed = unit(rng) < 0.05 ? 0.0 : 25.0 * unit(rng);
  const double aim = start_angle + pi + 0.6 * (2.0 * unit(rng) - 1.0);
  p.motion = {speed * unit_vector(aim), unit(rng) < 0.05 ? 0.0 : 3.0 * unit(rng)};
  return p;
}

/// The smallest signed distance of `distance_at(s)` at `steps` + 1 evenly spaced times of the motion.
template <class DistanceAt>
double densely_sampled_minimum(DistanceAt&& distance_at, double duration, int steps) {
  double low = distance_at(0.0);
  for (int k = 1; k <= steps; ++k) low = std::min(low, distance_at(duration * k / steps));
  return low;
}

constexpr int dense_steps = 4000;

TEST(translation_property, the_smallest_signed_distance_of_two_rectangles_is_the_densely_sampled_minimum) {
  std::mt19937_64 rng(testing::property_seed() + 41);
  const std::size_t count = testing::property_count(3000);
  std::size_t overlapping = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const random_pair p = draw(rng);
    const auto at = [&](double s) { return signed_distance(moved(p.a, s * p.motion.velocity), p.b); };
    const translation_minimum closed = smallest_signed_distance(p.a, p.b, p.motion);
    const double dense = densely_sampled_minimum(at, p.motion.duration, dense_steps);
    // Along a translation the signed distance changes no faster than the speed: between samples it
    // can dip by at most speed × half a step below the sampled minimum.
    const double slack = norm(p.motion.velocity) * p.motion.duration / dense_steps / 2.0 + 1e-9;
    ASSERT_LE(closed.distance, dense + 1e-9) << "trial " << trial << ": " << p.describe();
    ASSERT_GE(closed.distance, dense - slack) << "trial " << trial << ": " << p.describe();
    ASSERT_GE(closed.time, 0.0);
    ASSERT_LE(closed.time, p.motion.duration);
    ASSERT_NEAR(at(closed.time), closed.distance, 1e-9) << "trial " << trial << ": the minimum is taken at its time\n"
                                                       << p.describe();
    overlapping += closed.distance <= 0.0 ? 1 : 0;
  }
  EXPECT_GT(overlapping, count / 10) << "too few overlapping translations for the test to mean anything";
  EXPECT_LT(overlapping, count - count / 10) << "too few translations that stay apart";
}

TEST(translation_property, the_rectangle_and_disc_closed_forms_equal_the_general_polygon_form) {
  std::mt19937_64 rng(testing::property_seed() + 43);
  const std::size_t count = testing::property_count(3000);
  const auto polygon_of = [](const placed_rectangle& r) {
    const double x = r.half_length;
    const double y = r.half_width;
    return place(convex_polygon{{{x, y}, {-x, y}, {-x, -y}, {x, -y}}}, r.centre, r.axis);
  };
  for (std::size_t trial = 0; trial < count; ++trial) {
    const random_pair p = draw(rng);
    const translation_minimum closed = smallest_signed_distance(p.a, p.b, p.motion);
    const translation_minimum general = smallest_signed_distance(polygon_of(p.a), polygon_of(p.b), p.motion);
    ASSERT_NEAR(closed.distance, general.distance, 1e-9) << "trial " << trial << ": " << p.describe();
    // b as a disc of radius its half width; the general form with a point core, both ways round.
    const double radius = p.b.half_width;
    const translation_minimum disc_closed = smallest_signed_distance(p.a, p.b.centre, radius, p.motion);
    const translation_minimum disc_general =
        smallest_signed_distance(polygon_of(p.a), place(disc{radius}, p.b.centre, p.b.axis), p.motion);
    ASSERT_NEAR(disc_closed.distance, disc_general.distance, 1e-9) << "trial " << trial << ": " << p.describe();
    const translation reversed{-1.0 * p.motion.velocity, p.motion.duration};
    const translation_minimum swapped = smallest_signed_distance(place(disc{radius}, p.b.centre, p.b.axis),
                                                                 polygon_of(p.a), reversed);
    ASSERT_NEAR(disc_closed.distance, swapped.distance, 1e-9) << "trial " << trial << ": " << p.describe();
    const auto disc_at = [&](double s) { return signed_distance(moved(p.a, s * p.motion.velocity), p.b.centre, radius); };
    const double dense = densely_sampled_minimum(disc_at, p.motion.duration, dense_steps);
    const double slack = norm(p.motion.velocity) * p.motion.duration / dense_steps / 2.0 + 1e-9;
    ASSERT_LE(disc_closed.distance, dense + 1e-9) << "trial " << trial << ": " << p.describe();
    ASSERT_GE(disc_closed.distance, dense - slack) << "trial " << trial << ": " << p.describe();
  }
}

TEST(translation_property, threshold_tests_agree_with_the_minima_they_stand_for) {
  std::mt19937_64 rng(testing::property_seed() + 47);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(3000);
  std::size_t reached = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const random_pair p = draw(rng);
    const double level = 1.5 * (2.0 * unit(rng) - 1.0);
    const widening grows{level, 0.8 * (2.0 * unit(rng) - 1.0)};
    // The face separation reaches a widening level exactly when its minimum less the widening is ≤ 0.
    const double separation = smallest_face_separation(p.a, p.b, p.motion, grows).distance;
    if (std::abs(separation) > 1e-9) {
      ASSERT_EQ(face_separation_reaches(p.a, p.b, p.motion, grows), separation <= 0.0)
          << "trial " << trial << ": level " << level << " + " << grows.rate << " s\n" << p.describe();
    }
    const double radius = p.b.half_width;
    const double disc_separation = smallest_face_separation(p.a, p.b.centre, radius, p.motion, grows).distance;
    if (std::abs(disc_separation) > 1e-9) {
      ASSERT_EQ(face_separation_reaches(p.a, p.b.centre, radius, p.motion, grows), disc_separation <= 0.0)
          << "trial " << trial << ": level " << level << " + " << grows.rate << " s\n" << p.describe();
    }
    // The signed distance reaches a level exactly when its smallest value is at or below it.
    const double smallest = smallest_signed_distance(p.a, p.b, p.motion).distance;
    if (std::abs(smallest - level) > 1e-9) {
      ASSERT_EQ(signed_distance_reaches(p.a, p.b, p.motion, level), smallest <= level)
          << "trial " << trial << ": level " << level << "\n" << p.describe();
      reached += smallest <= level ? 1 : 0;
    }
    const double disc_smallest = smallest_signed_distance(p.a, p.b.centre, radius, p.motion).distance;
    if (std::abs(disc_smallest - level) > 1e-9) {
      ASSERT_EQ(signed_distance_reaches(p.a, p.b.centre, radius, p.motion, level), disc_smallest <= level)
          << "trial " << trial << ": level " << level << "\n" << p.describe();
    }
  }
  EXPECT_GT(reached, count / 10);
}

TEST(translation_property, the_first_contact_is_the_first_time_the_signed_distance_reaches_the_level) {
  std::mt19937_64 rng(testing::property_seed() + 53);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(1500);
  std::size_t contacts = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const random_pair p = draw(rng);
    const double level = 0.5 * unit(rng);
    const auto at = [&](double s) { return signed_distance(moved(p.a, s * p.motion.velocity), p.b); };
    const double first = first_contact(p.a, p.b, p.motion, level);
    const double smallest = smallest_signed_distance(p.a, p.b, p.motion).distance;
    if (smallest > level) {
      ASSERT_EQ(first, std::numeric_limits<double>::infinity()) << "trial " << trial << ": " << p.describe();
      continue;
    }
    ++contacts;
    ASSERT_LE(first, p.motion.duration) << "trial " << trial << ": " << p.describe();
    ASSERT_LE(at(first), level + 1e-6) << "trial " << trial << ": at its first contact\n" << p.describe();
    // No earlier time is within the level (beyond the bisection's resolution).
    const double before = first - 1e-6;
    if (before > 0.0) {
      const double earlier = densely_sampled_minimum(at, before, 400);
      ASSERT_GT(earlier, level - norm(p.motion.velocity) * before / 800.0 - 1e-9)
          << "trial " << trial << ": " << p.describe();
      ASSERT_GT(at(before), level) << "trial " << trial << ": " << p.describe();
    }
  }
  EXPECT_GT(contacts, count / 10);
}

TEST(translation_property, the_closest_approach_to_a_growing_disc_is_the_densely_sampled_minimum) {
  std::mt19937_64 rng(testing::property_seed() + 59);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> angle(-pi, pi);
  const std::size_t count = testing::property_count(3000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const vec2 offset = 30.0 * unit(rng) * unit_vector(angle(rng));
    const vec2 velocity = (unit(rng) < 0.05 ? 0.0 : 25.0 * unit(rng)) * unit_vector(angle(rng));
    const double growth = unit(rng) < 0.05 ? 0.0 : 30.0 * unit(rng);
    const double duration = 3.0 * unit(rng);
    const auto at = [&](double s) { return norm(offset + s * velocity) - growth * s; };
    const double closed = closest_approach_to_growing_disc(offset, velocity, growth, duration);
    const double dense = densely_sampled_minimum(at, duration, dense_steps);
    // The function changes no faster than |velocity| + growth.
    const double slack = (norm(velocity) + growth) * duration / dense_steps / 2.0 + 1e-9;
    const std::string input = "trial " + std::to_string(trial) + ": offset (" + std::to_string(offset.x) + ", " +
                              std::to_string(offset.y) + ") velocity (" + std::to_string(velocity.x) + ", " +
                              std::to_string(velocity.y) + ") growth " + std::to_string(growth) + " duration " +
                              std::to_string(duration);
    ASSERT_LE(closed, dense + 1e-9) << input;
    ASSERT_GE(closed, dense - slack) << input;
  }
}

TEST(translation, simple_translations_have_the_distances_and_contact_times_worked_out_by_hand) {
  const placed_rectangle a{{5.0, 1.0}, {1.0, 0.0}, 2.25, 0.9};
  const placed_rectangle b{{0.0, 0.0}, unit_vector(0.3), 2.25, 0.9};
  for (const translation motion : {translation{{0.0, 0.0}, 2.0}, translation{{-8.0, 0.5}, 0.0}}) {
    const translation_minimum m = smallest_signed_distance(a, b, motion);
    EXPECT_DOUBLE_EQ(m.distance, signed_distance(a, b));
    EXPECT_EQ(m.time, 0.0);
  }
  // Two aligned cars 5 m apart (centre to centre) along x, closing at 10 m/s: the gap of 0.5 m
  // closes after 0.05 s (a margin of 0.3 m is reached after 0.02 s).
  const placed_rectangle ahead{{0.0, 0.0}, {1.0, 0.0}, 2.25, 0.9};
  const placed_rectangle behind{{-5.0, 0.0}, {1.0, 0.0}, 2.25, 0.9};
  const translation closing{{10.0, 0.0}, 2.0};
  EXPECT_NEAR(first_contact(behind, ahead, closing, 0.0), 0.05, 1e-8);
  EXPECT_NEAR(first_contact(behind, ahead, closing, 0.3), 0.02, 1e-8);
  const translation_minimum deepest = smallest_signed_distance(behind, ahead, closing);
  // The width: the shortest way out is sideways, from when they overlap by 1.8 m along x (at 0.23 s)
  // to when they do again (0.77 s); the earliest time is reported.
  EXPECT_NEAR(deepest.distance, -1.8, 1e-12);
  EXPECT_NEAR(deepest.time, 0.23, 1e-12);
}

}  // namespace
}  // namespace mm
