#include "mm/sim/roundabout.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/drivable_area.hpp"
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

/// S2's roundabout (scenarios/s2-roundabout.yaml): four two-way arms, lanes 1.75 m either side.
struct s2_geometry {
  roundabout ring{{0.0, 0.0}, 25.0, 12.66};
  std::vector<roundabout_arm> arms{{0.0, 1.75, 60.0}, {pi / 2.0, 1.75, 60.0}, {pi, 1.75, 60.0}, {-pi / 2.0, 1.75, 60.0}};
};

/// The nearest distance [m] from `p` to the area's boundary.
double boundary_distance(const mm::drivable_area& area, vec2 p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const mm::segment& s : area.boundary()) nearest = std::min(nearest, mm::squared_distance_to_segment(p, s.a, s.b));
  return std::sqrt(nearest);
}

TEST(sim_roundabout, the_lanes_hold_every_route_with_half_a_lane_either_side) {
  const s2_geometry g;
  const double w = 3.5;
  const mm::drivable_area area(roundabout_lanes(g.ring, g.arms, w));
  for (std::size_t entry = 0; entry < g.arms.size(); ++entry) {
    for (std::size_t exit = 0; exit < g.arms.size(); ++exit) {
      const path route = roundabout_route(g.ring, g.arms[entry], g.arms[exit]);
      for (double s = 0.125; s < route.length(); s += 0.25) {  // not on the open ends' edges
        const path_point p = route.at(s);
        const vec2 left = mm::unit_vector(p.heading + pi / 2.0);
        // The chords lie within roundabout_lane_chord_error of the lane's true edges.
        const double inner = 0.5 * w - roundabout_lane_chord_error - 0.005;
        for (const double lateral : {0.0, inner, -inner}) {
          const vec2 q = p.position + lateral * left;
          ASSERT_TRUE(area.contains(q)) << "entry " << entry << ", exit " << exit << ", s = " << s << " m, "
                                        << lateral << " m to the left: (" << q.x << ", " << q.y << ")";
          // The boundary is half a lane away, less the chords' error, also where a merging lane's
          // edge meets the ring's tangentially (the ring's edge runs on inside the merging lane).
          if (lateral == 0.0) {
            ASSERT_GT(boundary_distance(area, q), 0.5 * w - roundabout_lane_chord_error - 1e-9)
                << "entry " << entry << ", exit " << exit << ", s = " << s << " of " << route.length() << " (" << q.x
                << ", " << q.y << ")";
          }
        }
      }
    }
  }
}

TEST(sim_roundabout, the_lanes_end_half_a_lane_beside_their_centre_lines_and_lead_on_at_the_arms_ends) {
  const s2_geometry g;
  const double w = 3.5;
  const mm::drivable_area area(roundabout_lanes(g.ring, g.arms, w));
  for (const double between_arms : {pi / 4.0, 3.0 * pi / 4.0, -pi / 4.0, -3.0 * pi / 4.0}) {
    // The ring alone, between the arms: R ± w/2 is its edge.
    EXPECT_TRUE(area.contains(ring_point(g.ring, between_arms)));
    for (const double radius : {25.0 - 0.5 * w - 0.05, 25.0 + 0.5 * w + 0.05}) {
      const vec2 outside = radius * mm::unit_vector(between_arms);
      EXPECT_FALSE(area.contains(outside)) << "angle " << between_arms << ", radius " << radius;
      EXPECT_LT(boundary_distance(area, outside), 0.05 + roundabout_lane_chord_error + 1e-9);
    }
  }
  for (const roundabout_arm& arm : g.arms) {
    const vec2 axis = mm::unit_vector(arm.angle);
    const vec2 left = mm::unit_vector(arm.angle + pi / 2.0);
    const vec2 middle = g.ring.center + 60.0 * axis;  // halfway along the arm's straights (μ ≈ 34.8 m)
    // w = 2o: the two lanes meet on the axis, with no boundary between them.
    EXPECT_TRUE(area.contains(middle + 0.01 * left) && area.contains(middle - 0.01 * left)) << "arm at " << arm.angle;
    EXPECT_GT(boundary_distance(area, middle), 2.0 * 1.75 - 1e-9);
    for (const double side : {1.0, -1.0}) {
      EXPECT_FALSE(area.contains(middle + side * (1.75 + 0.5 * w + 0.05) * left)) << "arm at " << arm.angle;
    }
    // The far end of the arm leads on: no boundary across it, only the lanes' sides end there.
    const path entry = roundabout_entry_route(g.ring, arm, pi / 2.0);
    const vec2 end = entry.at(0.0).position;
    EXPECT_GT(boundary_distance(area, end), 0.5 * w - 1e-9) << "arm at " << arm.angle;
    EXPECT_GT(boundary_distance(area, end + 2.0 * 1.75 * mm::unit_vector(arm.angle - pi / 2.0)), 0.5 * w - 1e-9);
  }
}

TEST(sim_roundabout, the_lanes_edges_are_a_lane_network_of_ring_pieces_between_junctions_and_the_arms_lanes) {
  const s2_geometry g;
  const double w = 3.5;
  const std::vector<lane_edges> lanes = roundabout_lane_edges(g.ring, g.arms, w);
  const mm::drivable_outline outline = roundabout_lanes(g.ring, g.arms, w);
  const std::size_t pieces = 2 * g.arms.size();  // S2's eight merge and diverge angles all differ
  ASSERT_EQ(lanes.size(), pieces + 2U * g.arms.size());
  const auto centre = [](const lane_edges& lane, std::size_t i) { return 0.5 * (lane.left[i] + lane.right[i]); };
  for (std::size_t l = 0; l < lanes.size(); ++l) {
    ASSERT_EQ(lanes[l].left.size(), lanes[l].right.size()) << "lane " << l;
    ASSERT_GE(lanes[l].left.size(), 2U) << "lane " << l;
    for (std::size_t i = 0; i < lanes[l].left.size(); ++i) {
      EXPECT_NEAR(mm::norm(lanes[l].left[i] - lanes[l].right[i]), w, 1e-9) << "lane " << l << ", cross-section " << i;
    }
    // A lane's successor starts where it ends.
    for (const std::size_t next : lanes[l].successors) {
      ASSERT_LT(next, lanes.size());
      EXPECT_LT(mm::norm(centre(lanes[l], lanes[l].left.size() - 1) - centre(lanes[next], 0)), 1e-9)
          << "lane " << l << " and its successor " << next;
    }
  }
  // The arms' lanes are the outline's last quadrilaterals {right_i, right_i+1, left_i+1, left_i}, in order.
  std::size_t arm_quads = 0;
  for (std::size_t l = pieces; l < lanes.size(); ++l) arm_quads += lanes[l].left.size() - 1;
  ASSERT_LE(arm_quads, outline.polygons.size());
  std::size_t quad = outline.polygons.size() - arm_quads;
  for (std::size_t l = pieces; l < lanes.size(); ++l) {
    const lane_edges& lane = lanes[l];
    for (std::size_t i = 0; i + 1 < lane.left.size(); ++i, ++quad) {
      const std::vector<vec2>& q = outline.polygons[quad];
      const vec2 expected[] = {lane.right[i], lane.right[i + 1], lane.left[i + 1], lane.left[i]};
      for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_LT(mm::norm(q[k] - expected[k]), 1e-9) << "lane " << l << ", cross-section " << i << ", vertex " << k;
      }
    }
  }
  // The ring's pieces: inner (left) edge R − w/2, outer (right) edge R + w/2, counter-clockwise,
  // each followed by the next, round to the first.
  for (std::size_t k = 0; k < pieces; ++k) {
    const lane_edges& piece = lanes[k];
    for (std::size_t i = 0; i < piece.left.size(); ++i) {
      EXPECT_NEAR(mm::norm(piece.left[i] - g.ring.center), 25.0 - 0.5 * w, 1e-9);
      EXPECT_NEAR(mm::norm(piece.right[i] - g.ring.center), 25.0 + 0.5 * w, 1e-9);
    }
    EXPECT_EQ(piece.successors.front(), (k + 1) % pieces) << "piece " << k;
    const vec2 from = piece.left.front() - g.ring.center;
    const vec2 to = piece.left.back() - g.ring.center;
    EXPECT_GT(from.x * to.y - from.y * to.x, 0.0) << "piece " << k << " turns counter-clockwise";
  }
  // Each entry ends at its merge angle and leads onto the piece that starts there; the piece that
  // ends at an exit's diverge angle leads onto that exit, which starts there.
  for (std::size_t a = 0; a < g.arms.size(); ++a) {
    const std::size_t entry = pieces + 2 * a;
    const std::size_t exit = entry + 1;
    const lane_edges& in = lanes[entry];
    EXPECT_LT(mm::norm(centre(in, in.left.size() - 1) - ring_point(g.ring, merge_angle(g.ring, g.arms[a]))), 1e-9);
    ASSERT_EQ(in.successors.size(), 1U);
    EXPECT_LT(in.successors.front(), pieces);
    EXPECT_LT(mm::norm(centre(lanes[exit], 0) - ring_point(g.ring, diverge_angle(g.ring, g.arms[a]))), 1e-9);
    EXPECT_TRUE(lanes[exit].successors.empty());
    std::size_t leading_to_exit = 0;
    for (std::size_t k = 0; k < pieces; ++k) {
      leading_to_exit += std::count(lanes[k].successors.begin(), lanes[k].successors.end(), exit);
    }
    EXPECT_EQ(leading_to_exit, 1U) << "arm " << a;
  }
  EXPECT_THROW(roundabout_lane_edges(g.ring, g.arms, 30.0), std::invalid_argument);
  const std::vector<lane_edges> ring_alone = roundabout_lane_edges(g.ring, {}, w);
  ASSERT_EQ(ring_alone.size(), 4U);
  EXPECT_NEAR(ring_alone[0].right.front().y, g.ring.center.y, 1e-9) << "the quarters start at polar angle 0";
}

TEST(sim_roundabout, lanes_too_wide_for_the_curves_or_not_positive_are_rejected) {
  const s2_geometry g;
  for (const double w : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), 2.0 * 12.66, 30.0}) {
    EXPECT_THROW(roundabout_lanes(g.ring, g.arms, w), std::invalid_argument) << "w = " << w;
  }
  try {
    roundabout_lanes(g.ring, g.arms, 26.0);
    FAIL() << "a lane wider than twice the connecting arcs' radius was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lane width = 26"), std::string::npos) << e.what();
  }
  EXPECT_THROW(roundabout_lanes(g.ring, std::vector<roundabout_arm>{{0.0, 30.0, 50.0}}, 3.5), std::invalid_argument);
  EXPECT_NO_THROW(roundabout_lanes(g.ring, {}, 3.5));  // the ring alone
  // A ring too large to draw in chords within 5 cm (1 − 0.05/R rounds to 1: no angle is small enough).
  const roundabout huge{{0.0, 0.0}, 1e20, 10.0};
  try {
    roundabout_lanes(huge, {}, 3.5);
    FAIL() << "a ring of 1e20 m was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected at most 1e+06"), std::string::npos) << e.what();
  }
  EXPECT_THROW(roundabout_lane_edges(huge, {}, 3.5), std::invalid_argument);
}

}  // namespace
