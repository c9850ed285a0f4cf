// The planning inputs maneuvermap_capture saves and maneuvermap_replan plans on (docs/performance.md).
#include "mm/plan_input_json.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

TEST(plan_input_json, a_saved_input_plans_to_the_same_result_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed());
  const std::size_t count = testing::property_count(6);
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {1 + trial % 3, trial % 2 == 1});
    in.config.safety_margin = trial % 3 == 0 ? 0.3 : 0.0;
    in.obstacles.front().shape = trial % 4 == 2 ? footprint{disc{0.4}} : in.obstacles.front().shape;
    if (trial % 2 == 0) {
      // A 7 m road along the ego's heading, its ends open: the road constraint binds.
      const vec2 along = unit_vector(in.ego.pose.heading);
      const vec2 across{-along.y, along.x};
      const vec2 c = in.ego.pose.position + 0.3 * across;
      in.drivable_area = std::make_shared<const drivable_area>(
          std::vector<std::vector<vec2>>{{c - 100.0 * along - 3.5 * across, c + 100.0 * along - 3.5 * across,
                                          c + 100.0 * along + 3.5 * across, c - 100.0 * along + 3.5 * across}},
          std::vector<polygon_edge>{{0, 1}, {0, 3}});
    }
    // Through text, as the tools do.
    const plan_input back = capture::plan_input_from_json(nlohmann::json::parse(capture::to_json(in).dump()));
    const plan_result a = plan(in);
    const plan_result b = plan(back);
    SCOPED_TRACE(testing::describe(in));
    ASSERT_TRUE(a.ok() && b.ok()) << a.error << b.error;
    EXPECT_EQ(a.mi_brake, b.mi_brake);
    EXPECT_EQ(a.mi_accelerate, b.mi_accelerate);
    EXPECT_EQ(a.command, b.command);
    EXPECT_EQ(a.forecast_index, b.forecast_index);
    EXPECT_EQ(a.work.bound_checks, b.work.bound_checks);
    EXPECT_EQ(a.on_drivable_area, b.on_drivable_area);
    ASSERT_EQ(back.drivable_area != nullptr, in.drivable_area != nullptr);
    if (in.drivable_area) {
      EXPECT_TRUE(a.on_drivable_area) << "the road binds the ego";
      EXPECT_EQ(back.drivable_area->polygons(), in.drivable_area->polygons());
      EXPECT_EQ(back.drivable_area->open_edges(), in.drivable_area->open_edges());
    }
    EXPECT_EQ(capture::to_json(back), capture::to_json(in)) << "a second round trip changes nothing";
  }
}

TEST(plan_input_json, a_missing_key_or_an_unknown_name_is_an_error_naming_it) {
  nlohmann::json j = capture::to_json(plan_input{});
  j["config"].erase("forecast_step");
  try {
    capture::plan_input_from_json(j);
    FAIL() << "accepted an input without config.forecast_step";
  } catch (const nlohmann::json::exception& e) {
    EXPECT_NE(std::string(e.what()).find("forecast_step"), std::string::npos) << e.what();
  }
  nlohmann::json policy = capture::to_json(plan_input{});
  policy["config"]["policy"] = "sometimes";
  EXPECT_THROW(capture::plan_input_from_json(policy), std::invalid_argument);
}

}  // namespace
}  // namespace mm
