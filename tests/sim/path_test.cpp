#include "mm/sim/path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "property.hpp"

namespace {

using mm::vec2;
using mm::sim::path;
constexpr double pi = std::numbers::pi;

TEST(sim_path, arc_length_parametrisation_of_an_arc_matches_the_circle) {
  const vec2 center{3.0, -2.0};
  const double radius = 10.0;
  const double start_angle = 0.3;
  const path arc = path::circular_arc(center, radius, start_angle, 2.0);
  EXPECT_NEAR(arc.length(), 20.0, 1e-12);
  for (double s = 0.0; s <= 20.0; s += 0.5) {
    const mm::sim::path_point p = arc.at(s);
    const double angle = start_angle + s / radius;
    EXPECT_NEAR(p.position.x, center.x + radius * std::cos(angle), 1e-9) << s;
    EXPECT_NEAR(p.position.y, center.y + radius * std::sin(angle), 1e-9) << s;
    EXPECT_NEAR(mm::wrap_angle(p.heading - (angle + pi / 2.0)), 0.0, 1e-12) << s;
    EXPECT_DOUBLE_EQ(p.curvature, 0.1);
  }
}

TEST(sim_path, a_clockwise_arc_has_negative_curvature_and_turns_right) {
  const path arc = path::circular_arc({0.0, 0.0}, 5.0, pi / 2.0, -pi / 2.0);
  EXPECT_NEAR(arc.length(), 5.0 * pi / 2.0, 1e-12);
  const mm::sim::path_point end = arc.at(arc.length());
  EXPECT_NEAR(end.position.x, 5.0, 1e-12);
  EXPECT_NEAR(end.position.y, 0.0, 1e-12);
  EXPECT_NEAR(end.heading, -pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(end.curvature, -0.2);
}

TEST(sim_path, polyline_length_is_the_sum_of_its_sides_and_headings_jump_at_corners) {
  const std::vector<vec2> points{{0.0, 0.0}, {3.0, 4.0}, {3.0, 10.0}};
  const path p = path::polyline(points);
  ASSERT_EQ(p.segments().size(), 2U);
  EXPECT_DOUBLE_EQ(p.length(), 11.0);
  EXPECT_NEAR(p.at(2.5).position.x, 1.5, 1e-12);
  EXPECT_NEAR(p.at(2.5).position.y, 2.0, 1e-12);
  EXPECT_NEAR(p.at(4.999).heading, std::atan2(4.0, 3.0), 1e-12);
  EXPECT_NEAR(p.at(5.0).heading, pi / 2.0, 1e-12);  // the later segment on the corner
  EXPECT_DOUBLE_EQ(p.at(5.0).curvature, 0.0);
}

TEST(sim_path, straight_and_turn_join_tangent_continuously) {
  path p(mm::pose{{0.0, 0.0}, 0.0});
  p.straight(10.0).turn(5.0, pi / 2.0).straight(10.0).turn(8.0, -pi / 4.0);
  EXPECT_NEAR(p.length(), 20.0 + 5.0 * pi / 2.0 + 8.0 * pi / 4.0, 1e-12);
  const mm::sim::path_point corner = p.at(10.0 + 5.0 * pi / 2.0);
  EXPECT_NEAR(corner.position.x, 15.0, 1e-12);
  EXPECT_NEAR(corner.position.y, 5.0, 1e-12);
  EXPECT_NEAR(corner.heading, pi / 2.0, 1e-12);
  // Every join: the end of one segment is the start of the next, in position and heading.
  const auto segments = p.segments();
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    const double s = segments[i + 1].start_arc_length;
    const mm::sim::path_point before = p.at(s - 1e-7);
    const mm::sim::path_point after = p.at(s + 1e-7);
    EXPECT_LT(mm::norm(before.position - after.position), 3e-7) << i;
    EXPECT_NEAR(mm::wrap_angle(before.heading - after.heading), 0.0, 1e-7) << i;
  }
  EXPECT_NEAR(p.end_pose().heading, pi / 4.0, 1e-12);
}

TEST(sim_path, projection_gives_the_arc_length_and_a_lateral_offset_positive_to_the_left) {
  const std::vector<vec2> points{{0.0, 0.0}, {100.0, 0.0}};
  const path road = path::polyline(points);
  const mm::sim::path_projection left = road.project({30.0, 2.0});
  EXPECT_DOUBLE_EQ(left.arc_length, 30.0);
  EXPECT_DOUBLE_EQ(left.lateral_offset, 2.0);
  const mm::sim::path_projection right = road.project({70.0, -3.0});
  EXPECT_DOUBLE_EQ(right.arc_length, 70.0);
  EXPECT_DOUBLE_EQ(right.lateral_offset, -3.0);
  EXPECT_DOUBLE_EQ(right.distance, 3.0);

  // Counter-clockwise circle: the inside is on the left; clockwise: on the right.
  const path ccw = path::circular_arc({0.0, 0.0}, 10.0, 0.0, pi);
  const mm::sim::path_projection inside = ccw.project({0.0, 8.0});
  EXPECT_NEAR(inside.arc_length, 10.0 * pi / 2.0, 1e-9);
  EXPECT_NEAR(inside.lateral_offset, 2.0, 1e-9);
  EXPECT_NEAR(ccw.project({-13.0 * std::sqrt(0.5), 13.0 * std::sqrt(0.5)}).lateral_offset, -3.0, 1e-9);
  const path cw = path::circular_arc({0.0, 0.0}, 10.0, pi, -pi);
  EXPECT_NEAR(cw.project({0.0, 8.0}).lateral_offset, -2.0, 1e-9);
  EXPECT_NEAR(cw.project({0.0, 8.0}).arc_length, 10.0 * pi / 2.0, 1e-9);
}

TEST(sim_path, projection_continues_along_the_end_tangents_beyond_the_ends) {
  path p(mm::pose{{0.0, 0.0}, pi / 2.0});
  p.straight(10.0);
  const mm::sim::path_projection before = p.project({-1.0, -4.0});
  EXPECT_DOUBLE_EQ(before.arc_length, -4.0);
  EXPECT_DOUBLE_EQ(before.lateral_offset, 1.0);  // west of a north-bound road: left
  const mm::sim::path_projection after = p.project({2.0, 15.0});
  EXPECT_DOUBLE_EQ(after.arc_length, 15.0);
  EXPECT_DOUBLE_EQ(after.lateral_offset, -2.0);
  EXPECT_DOUBLE_EQ(p.at(15.0).position.y, 15.0);
  EXPECT_DOUBLE_EQ(p.at(-4.0).position.y, -4.0);
}

TEST(sim_path, projection_with_a_hint_stays_on_the_branch_of_a_hairpin) {
  // Out east along y = 0, back west along y = 1.
  const std::vector<vec2> points{{0.0, 0.0}, {50.0, 0.0}, {50.0, 1.0}, {0.0, 1.0}};
  const path hairpin = path::polyline(points);
  const vec2 point{20.0, 0.4};
  const mm::sim::path_projection global = hairpin.project(point);
  EXPECT_DOUBLE_EQ(global.arc_length, 20.0);
  EXPECT_NEAR(global.lateral_offset, 0.4, 1e-12);
  const double return_branch = 50.0 + 1.0 + 30.0;
  const mm::sim::path_projection hinted = hairpin.project(point, return_branch, 5.0);
  EXPECT_NEAR(hinted.arc_length, return_branch, 1e-12);
  EXPECT_NEAR(hinted.lateral_offset, 0.6, 1e-12);  // south of a west-bound lane is its left
}

TEST(sim_path, an_arc_longer_than_a_lap_projects_within_the_hint_window) {
  const path loops = path::circular_arc({0.0, 0.0}, 10.0, 0.0, 4.0 * pi);
  const double lap = 20.0 * pi;
  const mm::sim::path_projection second_lap = loops.project({0.0, 10.5}, lap + 5.0 * pi, 3.0);
  EXPECT_NEAR(second_lap.arc_length, lap + 5.0 * pi, 1e-9);
  EXPECT_NEAR(second_lap.lateral_offset, -0.5, 1e-9);
  EXPECT_NEAR(loops.project({0.0, 10.5}).arc_length, 5.0 * pi, 1e-9);
}

TEST(sim_path, invalid_pieces_are_rejected) {
  path p(mm::pose{});
  EXPECT_THROW(p.straight(0.0), std::invalid_argument);
  EXPECT_THROW(p.turn(-1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(p.turn(5.0, 0.0), std::invalid_argument);
  EXPECT_THROW(p.line_to({0.0, 0.0}), std::invalid_argument);
  const std::vector<vec2> one{{1.0, 1.0}};
  EXPECT_THROW(path::polyline(one), std::invalid_argument);
  EXPECT_TRUE(path().empty());
}

TEST(sim_path, the_steps_of_a_path_rebuild_it_bit_for_bit) {
  // Random paths of every operation, polylines and arcs of several laps.
  std::mt19937_64 rng(mm::testing::property_seed() + 7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    path p(mm::pose{{200.0 * unit(rng) - 100.0, 200.0 * unit(rng) - 100.0}, 8.0 * unit(rng) - 4.0});
    const int pieces = 1 + trial % 6;
    for (int k = 0; k < pieces; ++k) {
      const double pick = unit(rng);
      if (pick < 0.25) {
        p.straight(0.01 + 50.0 * unit(rng));
      } else if (pick < 0.5) {
        p.turn(1.0 + 40.0 * unit(rng), (unit(rng) < 0.5 ? -1.0 : 1.0) * (0.01 + 7.0 * unit(rng)));
      } else if (pick < 0.75) {
        p.line_to(p.end_pose().position + vec2{30.0 * unit(rng) - 15.0, 30.0 * unit(rng) + 0.5});
      } else {
        p.curve(0.01 + 30.0 * unit(rng), 0.4 * unit(rng) - 0.2);
      }
    }
    const mm::sim::path_steps steps = mm::sim::steps_of(p);
    ASSERT_EQ(steps.steps.size(), p.segments().size());
    ASSERT_TRUE(mm::sim::path_of(steps) == p) << "trial " << trial << " (seed " << mm::testing::property_seed() << ")";
  }
  const std::vector<vec2> corners{{0.0, 0.0}, {3.0, 4.0}, {3.0, 9.0}, {-2.0, 9.0}};
  for (const path& p : {path::polyline(corners), path::circular_arc({5.0, 5.0}, 25.0, -0.5, 9.0), path(),
                        path(mm::pose{{4.0, 5.0}, 1.0})}) {
    EXPECT_TRUE(mm::sim::path_of(mm::sim::steps_of(p)) == p);
  }
  // A polyline's corners are line_to steps, a straight continuation a straight step.
  const mm::sim::path_steps corner_steps = mm::sim::steps_of(path::polyline(corners));
  EXPECT_EQ(corner_steps.steps[1].operation, mm::sim::path_step::kind::line_to);
  EXPECT_EQ(corner_steps.steps[1].point, corners[2]);
  const mm::sim::path_steps straight_steps = mm::sim::steps_of(path(mm::pose{}).straight(3.0).straight(4.0));
  EXPECT_EQ(straight_steps.steps[1].operation, mm::sim::path_step::kind::straight);
  EXPECT_EQ(straight_steps.steps[1].length, 4.0);
}

}  // namespace
