// The shapes of recorded obstacles as world polygons (`world_polygon`) and the lanelets as a drivable
// area (`lanelet_polygons`), commonroad/src/recording.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/commonroad/scenario.hpp"

namespace {

using namespace mm::commonroad;

state at(mm::vec2 position, double orientation) { return {0, position, orientation, 0.0, std::nullopt, std::nullopt}; }

TEST(world_polygon, a_rectangle_has_its_four_corners_placed_at_the_recorded_pose) {
  const std::vector<mm::vec2> corners = world_polygon(mm::rectangle{4.0, 2.0}, at({10.0, 5.0}, std::numbers::pi / 2));
  ASSERT_EQ(corners.size(), 4U);
  // Turned a quarter to the left: the length along y, the width along x.
  for (const mm::vec2 c : corners) {
    EXPECT_NEAR(std::abs(c.x - 10.0), 1.0, 1e-12) << c.x << ", " << c.y;
    EXPECT_NEAR(std::abs(c.y - 5.0), 2.0, 1e-12) << c.x << ", " << c.y;
  }
  // Counter-clockwise: positive signed area, 8 m².
  double twice = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const mm::vec2 a = corners[i];
    const mm::vec2 b = corners[(i + 1) % corners.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  EXPECT_NEAR(0.5 * twice, 8.0, 1e-9);
}

TEST(world_polygon, a_disc_is_the_regular_16_gon_around_it_never_smaller) {
  const double radius = 0.5;
  const mm::vec2 centre{-3.0, 7.0};
  const std::vector<mm::vec2> corners = world_polygon(mm::disc{radius}, at(centre, 1.0));
  ASSERT_EQ(corners.size(), 16U);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const mm::vec2 a = corners[i] - centre;
    const mm::vec2 b = corners[(i + 1) % corners.size()] - centre;
    EXPECT_NEAR(std::hypot(a.x, a.y), radius / std::cos(std::numbers::pi / 16.0), 1e-12) << i;
    // Each side touches the disc at its middle.
    EXPECT_NEAR(std::hypot(0.5 * (a.x + b.x), 0.5 * (a.y + b.y)), radius, 1e-12) << i;
  }
}

TEST(lanelet_polygons, a_lanelet_is_its_left_bound_and_its_right_bound_backwards_with_open_ends) {
  mm::commonroad::scenario s;
  s.lanelets.push_back({7, {{0, 2}, {10, 2}, {20, 2}}, {{0, -2}, {20, -2}}, {}, {}});
  const mm::drivable_outline outline = mm::commonroad::lanelet_polygons(s);
  ASSERT_EQ(outline.polygons.size(), 1U);
  EXPECT_EQ(outline.polygons[0], (std::vector<mm::vec2>{{0, 2}, {10, 2}, {20, 2}, {20, -2}, {0, -2}}));
  // Its end (from the left bound's last point to the right's) and its start lead on.
  EXPECT_EQ(outline.open_edges, (std::vector<mm::polygon_edge>{{0, 2}, {0, 4}}));
  const mm::drivable_area area(outline);
  double length = 0.0;
  for (const mm::segment& e : area.boundary()) length += mm::norm(e.b - e.a);
  EXPECT_NEAR(length, 40.0, 1e-9) << "only its two bounds are boundary";
  // A lanelet whose bounds enclose nothing is named.
  s.lanelets.push_back({8, {{0, 0}, {10, 0}}, {{0, 0}, {10, 0}}, {}, {}});
  try {
    (void)mm::commonroad::lanelet_polygons(s);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lanelet 8"), std::string::npos) << e.what();
  }
}

}  // namespace
