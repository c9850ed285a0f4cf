#include "mm/drivable_area.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace mm {
namespace {

/// The rectangle [x0, x1] × [y0, y1], counter-clockwise.
std::vector<vec2> box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

double total_length(const std::vector<segment>& segments) {
  double length = 0.0;
  for (const segment& s : segments) length += norm(s.b - s.a);
  return length;
}

/// True when the union lies on exactly one side of the segment's middle.
bool separates_inside_from_outside(const drivable_area& area, const segment& s) {
  const vec2 along = s.b - s.a;
  const vec2 left = (1.0 / norm(along)) * vec2{-along.y, along.x};
  const vec2 middle = s.a + 0.5 * along;
  return area.contains(middle + 0.01 * left) != area.contains(middle - 0.01 * left);
}

TEST(drivable_area, two_crossing_roads_are_bounded_by_their_union_not_by_the_edges_inside_each_other) {
  // Two 3.5 m roads, 40 m long, crossing at the origin: a cross whose perimeter is the two
  // rectangles' less the four 3.5 m pieces of their long edges that lie inside the other road.
  const drivable_area area({box(-20.0, -1.75, 20.0, 1.75), box(-1.75, -20.0, 1.75, 20.0)});
  EXPECT_NEAR(total_length(area.boundary()), 2.0 * 2.0 * (40.0 + 3.5) - 4.0 * 3.5, 1e-9);
  for (const segment& s : area.boundary()) EXPECT_TRUE(separates_inside_from_outside(area, s));
  // Twelve corners: twelve segments (the pieces of one edge on either side of the crossing are two).
  EXPECT_EQ(area.boundary().size(), 12U);
  EXPECT_TRUE(area.contains({0.0, 0.0}));
  EXPECT_TRUE(area.contains({15.0, 1.0}));
  EXPECT_FALSE(area.contains({5.0, 5.0}));
}

TEST(drivable_area, neighbouring_lanes_that_share_a_bound_make_one_road_without_an_edge_between_them) {
  // Two lanes, the second given clockwise, sharing y = 0; and a pair whose shared bound is 2 cm off
  // (as neighbouring lanelets of recorded maps are: each samples the bound at its own points).
  const drivable_area two({box(0.0, -3.5, 100.0, 0.0), {{0.0, 0.0}, {0.0, 3.5}, {100.0, 3.5}, {100.0, 0.0}}});
  EXPECT_NEAR(total_length(two.boundary()), 2.0 * (100.0 + 7.0), 1e-9);
  for (const segment& s : two.boundary()) {
    EXPECT_FALSE(std::abs(s.a.y) < 1e-9 && std::abs(s.b.y) < 1e-9) << "no boundary along the shared bound";
  }
  const drivable_area near({box(0.0, -3.5, 100.0, 0.0), box(0.0, 0.02, 100.0, 3.5)});
  // Its boundary: the outer long edges, and the lanes' ends (the 2 cm between them is no edge).
  EXPECT_NEAR(total_length(near.boundary()), 2.0 * 100.0 + 2.0 * (7.0 - 0.02), 1e-9) << "the 2 cm gap is closed";
  // A gap wider than the closing distance is not a road: both of its sides are boundary.
  const drivable_area apart({box(0.0, -3.5, 100.0, 0.0), box(0.0, 0.25, 100.0, 3.75)});
  EXPECT_NEAR(total_length(apart.boundary()), 2.0 * 2.0 * (100.0 + 3.5), 1e-9);
}

TEST(drivable_area, a_road_with_a_branch_keeps_the_edge_pieces_beside_the_branch) {
  // A T: the main road's north edge is boundary left and right of the branch, not where it joins.
  const drivable_area area({box(-50.0, -3.5, 50.0, 3.5), box(-3.0, 0.0, 3.0, 40.0)});
  double on_north_edge = 0.0;
  for (const segment& s : area.boundary()) {
    if (std::abs(s.a.y - 3.5) < 1e-12 && std::abs(s.b.y - 3.5) < 1e-12) on_north_edge += std::abs(s.b.x - s.a.x);
  }
  EXPECT_NEAR(on_north_edge, 100.0 - 6.0, 1e-9);
  for (const segment& s : area.boundary()) EXPECT_TRUE(separates_inside_from_outside(area, s));
}

TEST(drivable_area, an_edge_that_runs_on_inside_another_lane_near_its_edge_is_no_boundary) {
  // Two lanes overlapping over x = 50..100, the second shifted 5 cm to the left: along the overlap
  // each one's edge lies 5 cm inside the other (closer than the probes' 0.1 m), and only the outer
  // edges bound the road; where one lane ends, the 5 cm step between their edges is boundary.
  const drivable_area area({box(0.0, -1.75, 100.0, 1.75), box(50.0, -1.70, 150.0, 1.80)});
  EXPECT_NEAR(total_length(area.boundary()), 2.0 * (100.0 + 3.5 + 50.0 + 0.05), 1e-9);
  for (const segment& s : area.boundary()) {
    const vec2 middle = 0.5 * (s.a + s.b);
    EXPECT_FALSE(middle.x > 50.0 && middle.x < 100.0 && std::abs(middle.y) < 1.75)
        << "an inner edge at (" << middle.x << ", " << middle.y << ")";
  }
  // A lane within a wider one, 5 cm from its edges, adds no boundary.
  const drivable_area nested({box(0.0, -1.75, 100.0, 1.75), box(20.0, -1.70, 60.0, 1.70)});
  EXPECT_NEAR(total_length(nested.boundary()), 2.0 * (100.0 + 3.5), 1e-9);
}

TEST(drivable_area, open_edges_lead_on_beyond_the_map_and_are_no_boundary) {
  // A road whose two ends (edges 1 and 3 of the box) lead on: only its sides bound it; a second
  // piece continuing it past x = 100 with its own open ends keeps that so.
  const drivable_area road({box(0.0, -1.75, 100.0, 1.75), box(100.0, -1.75, 150.0, 1.75)}, {{0, 1}, {0, 3}, {1, 1}, {1, 3}});
  EXPECT_NEAR(total_length(road.boundary()), 2.0 * 150.0, 1e-9);
  for (const segment& s : road.boundary()) EXPECT_NEAR(std::abs(s.a.y), 1.75, 1e-12);
  // The same without open edges: closed at x = 0 and x = 150.
  const drivable_area closed({box(0.0, -1.75, 100.0, 1.75), box(100.0, -1.75, 150.0, 1.75)});
  EXPECT_NEAR(total_length(closed.boundary()), 2.0 * 150.0 + 2.0 * 3.5, 1e-9);
}

TEST(drivable_area, bad_polygons_are_refused_with_the_polygon_the_vertex_and_what_was_expected) {
  EXPECT_NE(drivable_area_error({})->find("no polygon"), std::string::npos);
  EXPECT_NE(drivable_area_error({box(0, 0, 1, 1), {{0.0, 0.0}, {1.0, 0.0}}})->find("polygons[1] has 2 vertices"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto not_finite = drivable_area_error({{{0.0, 0.0}, {1.0, 0.0}, {1.0, nan}}});
  ASSERT_TRUE(not_finite);
  EXPECT_NE(not_finite->find("polygons[0][2]"), std::string::npos) << *not_finite;
  EXPECT_NE(not_finite->find("expected finite coordinates"), std::string::npos) << *not_finite;
  const auto flat = drivable_area_error({{{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}}});
  ASSERT_TRUE(flat);
  EXPECT_NE(flat->find("polygons[0] has no area"), std::string::npos) << *flat;
  EXPECT_FALSE(drivable_area_error({box(0, 0, 1, 1)}));
  EXPECT_THROW(drivable_area(std::vector<std::vector<vec2>>{}), std::invalid_argument);
  const std::vector<std::vector<vec2>> too_many(largest_drivable_vertex_count / 4 + 1, box(0, 0, 1, 1));
  EXPECT_NE(drivable_area_error(too_many)->find("100004 vertices in all; expected at most 100000"), std::string::npos);
  const auto no_such_edge = drivable_area_error({box(0, 0, 1, 1)}, {{0, 3}, {0, 4}});
  ASSERT_TRUE(no_such_edge);
  EXPECT_NE(no_such_edge->find("open_edges[1] = edge 4 of polygon 0"), std::string::npos) << *no_such_edge;
}

TEST(drivable_area, a_footprint_s_signed_distance_to_a_segment_is_its_gap_or_minus_its_penetration) {
  const placed_footprint car = place(rectangle{4.5, 1.8}, {{0.0, 0.0}, 0.0});
  // A kerb line along y = 1.5 m: 0.6 m clear of the car's left side at y = 0.9 m.
  EXPECT_NEAR(signed_distance(car, segment{{-10.0, 1.5}, {10.0, 1.5}}), 0.6, 1e-12);
  // Along y = 0.5: it cuts the car, which must move 0.4 m to the right (or 1.4 m left) to clear it.
  EXPECT_NEAR(signed_distance(car, segment{{-10.0, 0.5}, {10.0, 0.5}}), -0.4, 1e-12);
  // A short segment ahead, end-on: the gap from the car's front (x = 2.25) to its end.
  EXPECT_NEAR(signed_distance(car, segment{{3.0, 0.0}, {8.0, 0.0}}), 0.75, 1e-12);
  // The same segment poking 0.25 m into the front: the shortest way out is back along it.
  EXPECT_NEAR(signed_distance(car, segment{{2.0, 0.0}, {8.0, 0.0}}), -0.25, 1e-12);
  // Past a corner: the distance to the corner.
  EXPECT_NEAR(signed_distance(car, segment{{3.25, 1.9}, {3.25, 5.0}}), std::hypot(1.0, 1.0), 1e-12);
  // A disc of 0.35 m: its centre's distance less the radius, negative when the line runs through it.
  const placed_footprint walker = place(disc{0.35}, {{0.0, 0.0}, 0.0});
  EXPECT_NEAR(signed_distance(walker, segment{{-1.0, 1.0}, {1.0, 1.0}}), 0.65, 1e-12);
  EXPECT_NEAR(signed_distance(walker, segment{{-1.0, 0.1}, {1.0, 0.1}}), -0.25, 1e-12);
}

TEST(drivable_area, the_boundary_clearance_is_the_nearest_segment_s_and_capped) {
  const drivable_area road({box(-100.0, -1.75, 100.0, 1.75)});
  const placed_footprint car = place(rectangle{4.5, 1.8}, {{0.0, 0.5}, 0.0});
  // The north edge is 1.75 − 1.4 = 0.35 m from the car's left side, the south edge 1.75 + 0.5 − 0.9.
  EXPECT_NEAR(boundary_clearance(road.boundary(), car, 2.0), 0.35, 1e-12);
  EXPECT_EQ(boundary_clearance(road.boundary(), car, 0.2), 0.2) << "capped";
  const placed_footprint across = place(rectangle{4.5, 1.8}, {{0.0, 0.0}, std::numbers::pi / 2.0});
  EXPECT_LT(boundary_clearance(road.boundary(), across, 2.0), 0.0) << "a car across a 3.5 m road crosses its edges";
}

TEST(drivable_area, the_boundary_s_lines_are_its_segments_and_give_the_same_clearances_bit_for_bit) {
  const drivable_area area({box(-100.0, -1.75, 100.0, 1.75), box(20.0, -50.0, 23.5, 50.0)});
  ASSERT_EQ(area.boundary_lines().size(), area.boundary().size());
  for (std::size_t i = 0; i < area.boundary().size(); ++i) {
    const segment& s = area.boundary()[i];
    const segment_line& line = area.boundary_lines()[i];
    EXPECT_EQ(line.a, s.a);
    EXPECT_EQ(line.b, s.b);
    EXPECT_NEAR(line.length, norm(s.b - s.a), 1e-12);
    EXPECT_NEAR(norm(line.direction), 1.0, 1e-12);
  }
  for (double x = -5.0; x <= 30.0; x += 0.7) {
    for (const double heading : {0.0, 0.4, 1.3, 2.9}) {
      const placed_footprint car = place(rectangle{4.5, 1.8}, {{x, 0.3 * std::sin(x)}, heading});
      for (const double cap : {0.5, 2.0, std::numeric_limits<double>::infinity()}) {
        EXPECT_EQ(boundary_clearance(area.boundary_lines(), car, cap), boundary_clearance(area.boundary(), car, cap))
            << "x " << x << " heading " << heading << " cap " << cap;
      }
    }
  }
}

}  // namespace
}  // namespace mm
