#include "mm/sim/roundabout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "mm/maneuver.hpp"

namespace {

using mm::vec2;
using namespace mm::sim;
constexpr double pi = std::numbers::pi;

/// Every join of `p` is continuous in position and heading (G¹).
void expect_tangent_continuous(const path& p) {
  const auto segments = p.segments();
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    const path_segment& a = segments[i];
    const path_segment& b = segments[i + 1];
    const vec2 end = mm::to_world(a.start, mm::arc_point(a.curvature, a.length));
    EXPECT_LT(mm::norm(end - b.start.position), 1e-9) << "join " << i;
    EXPECT_NEAR(mm::wrap_angle(a.start.heading + a.curvature * a.length - b.start.heading), 0.0, 1e-9)
        << "join " << i;
  }
}

TEST(sim_roundabout, merge_and_diverge_angles_follow_the_tangent_circle_construction) {
  const roundabout ring{{0.0, 0.0}, 25.0, 20.0};
  const roundabout_arm arm{1.0, 0.0, 50.0};
  const double delta = std::asin(20.0 / 45.0);  // o = 0: sin δ = r / (R + r)
  EXPECT_NEAR(merge_angle(ring, arm), 1.0 + delta, 1e-12);
  EXPECT_NEAR(diverge_angle(ring, arm), 1.0 - delta, 1e-12);
  const roundabout_arm offset{1.0, 2.0, 50.0};
  EXPECT_NEAR(merge_angle(ring, offset), 1.0 + std::atan2(22.0, std::sqrt(45.0 * 45.0 - 22.0 * 22.0)), 1e-12);
}

TEST(sim_roundabout, a_route_enters_circulates_counter_clockwise_and_leaves_tangent_continuously) {
  const roundabout ring{{10.0, -5.0}, 25.0, 20.0};
  const roundabout_arm south{-pi / 2.0, 1.75, 40.0};
  const roundabout_arm north{pi / 2.0, 1.75, 30.0};
  const path route = roundabout_route(ring, south, north);
  ASSERT_EQ(route.segments().size(), 5U);
  expect_tangent_continuous(route);

  const auto seg = route.segments();
  // Approach: heading north (towards the centre), 1.75 m right of the south arm's axis (x = 11.75).
  EXPECT_NEAR(seg[0].start.heading, pi / 2.0, 1e-12);
  EXPECT_NEAR(seg[0].start.position.x, 11.75, 1e-12);
  EXPECT_DOUBLE_EQ(seg[0].length, 40.0);
  // Connecting arcs turn right with radius r; the ring turns left with radius R.
  EXPECT_DOUBLE_EQ(seg[1].curvature, -1.0 / 20.0);
  EXPECT_DOUBLE_EQ(seg[2].curvature, 1.0 / 25.0);
  EXPECT_DOUBLE_EQ(seg[3].curvature, -1.0 / 20.0);
  // The ring piece starts at the merge point and ends at the diverge point, on the circle.
  const vec2 merge = ring_point(ring, merge_angle(ring, south));
  EXPECT_LT(mm::norm(seg[2].start.position - merge), 1e-9);
  const vec2 diverge = ring_point(ring, diverge_angle(ring, north));
  const vec2 ring_end = mm::to_world(seg[2].start, mm::arc_point(seg[2].curvature, seg[2].length));
  EXPECT_LT(mm::norm(ring_end - diverge), 1e-9);
  for (double s = seg[2].start_arc_length; s <= seg[3].start_arc_length; s += 1.0) {
    EXPECT_NEAR(mm::norm(route.at(s).position - ring.center), 25.0, 1e-9);
  }
  // Departure: heading north along the north arm, 1.75 m right of its axis (x = 11.75 again).
  const path_point end = route.at(route.length());
  EXPECT_NEAR(end.heading, pi / 2.0, 1e-9);
  EXPECT_NEAR(end.position.x, 11.75, 1e-9);
  EXPECT_NEAR(seg[4].length, 30.0, 1e-12);
  // Half a lap minus the two junction angles on the ring.
  const double swept = pi - 2.0 * std::atan2(21.75, std::sqrt(45.0 * 45.0 - 21.75 * 21.75));
  EXPECT_NEAR(seg[2].length, 25.0 * swept, 1e-9);
}

TEST(sim_roundabout, an_exit_route_leaves_by_the_exit_before_the_entry_as_in_scenario_s2) {
  // S2: A enters from the east arm; B circulates and leaves by the arm 45° of arc before it.
  const roundabout ring{{0.0, 0.0}, 25.0, 20.0};
  const roundabout_arm a_entry{0.0, 0.0, 60.0};
  const roundabout_arm b_exit{-pi / 4.0, 0.0, 60.0};
  const double b_start = -pi;  // B starts on the ring, half a lap before A's entry arm
  const path b = roundabout_exit_route(ring, b_start, b_exit);
  expect_tangent_continuous(b);
  const double ring_length = 25.0 * (diverge_angle(ring, b_exit) - b_start);
  EXPECT_NEAR(b.segments()[0].length, ring_length, 1e-9);
  EXPECT_LT(diverge_angle(ring, b_exit), merge_angle(ring, a_entry));  // B leaves before A merges
  EXPECT_NEAR(b.at(b.length()).heading, -pi / 4.0, 1e-9);
  // Had B stayed on the ring it would reach A's merge point after R·(ψ_A − ψ_B0) metres.
  const path stay = roundabout_ring(ring, b_start, 2.0 * pi);
  const double to_merge = 25.0 * (merge_angle(ring, a_entry) - b_start);
  EXPECT_LT(mm::norm(stay.at(to_merge).position - ring_point(ring, merge_angle(ring, a_entry))), 1e-9);

  const path a = roundabout_entry_route(ring, a_entry, pi);
  expect_tangent_continuous(a);
  EXPECT_NEAR(a.at(0.0).heading, pi, 1e-12);  // driving west, towards the centre
}

TEST(sim_roundabout, invalid_geometry_is_rejected) {
  const roundabout ring{{0.0, 0.0}, 25.0, 20.0};
  EXPECT_THROW(merge_angle(ring, {0.0, 30.0, 50.0}), std::invalid_argument);  // lane offset beyond the ring
  EXPECT_THROW(roundabout_route(ring, {0.0, 0.0, -1.0}, {1.0, 0.0, 10.0}), std::invalid_argument);
  EXPECT_THROW(roundabout_ring(ring, 0.0, -1.0), std::invalid_argument);
  EXPECT_THROW(roundabout_route(roundabout{{0.0, 0.0}, 0.0, 20.0}, {}, {}), std::invalid_argument);
}

}  // namespace
