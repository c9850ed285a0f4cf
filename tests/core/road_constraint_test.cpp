// The road constraint of spec §5 on random scenes and roads: the fast road field against its
// reference, the continuous-time proof against a dense scan, and the planner with a road against
// the planner without one and against the reference planner (spec §11).
#include "mm/road_constraint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>

#include "mm/planner.hpp"
#include "mm/reference_planner.hpp"
#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

/// A rectangle `length` × `width` [m] centred at `centre`, its length along `heading` [rad].
std::vector<vec2> road_piece(vec2 centre, double heading, double length, double width) {
  const vec2 along = unit_vector(heading);
  const vec2 across{-along.y, along.x};
  const vec2 l = 0.5 * length * along;
  const vec2 w = 0.5 * width * across;
  return {centre - l - w, centre + l - w, centre + l + w, centre - l + w};
}

/// A straight road about the ego (3 to 8 m wide, the ego up to 1.5 m off its middle, at up to 0.3 rad
/// to it), in half of the trials crossed by a second road 5 to 25 m ahead at a random angle, and in
/// a quarter of them ending 10 to 40 m ahead.
std::shared_ptr<const drivable_area> random_road(std::mt19937_64& rng, const ego_state& ego) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double heading = ego.pose.heading + 0.6 * (unit(rng) - 0.5);
  const vec2 along = unit_vector(heading);
  const vec2 across{-along.y, along.x};
  const double width = 3.0 + 5.0 * unit(rng);
  const double offset = 3.0 * (unit(rng) - 0.5);
  const bool dead_end = unit(rng) < 0.25;
  const double ahead = dead_end ? 10.0 + 30.0 * unit(rng) : 150.0;
  const vec2 middle = ego.pose.position + offset * across + (0.5 * (ahead - 150.0)) * along;
  std::vector<std::vector<vec2>> pieces{road_piece(middle, heading, ahead + 150.0, width)};
  if (unit(rng) < 0.5) {
    const vec2 crossing = ego.pose.position + (5.0 + 20.0 * unit(rng)) * unit_vector(ego.pose.heading);
    pieces.push_back(road_piece(crossing, heading + 0.4 + 2.3 * unit(rng), 200.0, 3.0 + 5.0 * unit(rng)));
  }
  return std::make_shared<const drivable_area>(std::move(pieces));
}

/// A curved road about the ego: a ring of chords (0.05 rad each) 3 to 8 m wide, its centre line
/// through a point up to 1.5 m beside the ego, bending left or right with a radius of 8 to 60 m:
/// many boundary segments near the ego, and an inner edge whose chords' lines pass near it.
std::shared_ptr<const drivable_area> random_curved_road(std::mt19937_64& rng, const ego_state& ego) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double heading = ego.pose.heading + 0.6 * (unit(rng) - 0.5);
  const vec2 left = unit_vector(heading + 0.5 * std::numbers::pi);
  const double width = 3.0 + 5.0 * unit(rng);
  const double radius = 8.0 + 52.0 * unit(rng);
  const double side = unit(rng) < 0.5 ? 1.0 : -1.0;
  const vec2 centre = ego.pose.position + (side * radius + 3.0 * (unit(rng) - 0.5)) * left;
  const std::size_t chords = static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi / 0.05));
  std::vector<std::vector<vec2>> pieces;
  for (std::size_t i = 0; i < chords; ++i) {
    const vec2 a = unit_vector(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(chords));
    const vec2 b = unit_vector(2.0 * std::numbers::pi * static_cast<double>(i + 1) / static_cast<double>(chords));
    const double inner = radius - 0.5 * width;
    const double outer = radius + 0.5 * width;
    pieces.push_back({centre + inner * a, centre + outer * a, centre + outer * b, centre + inner * b});
  }
  return std::make_shared<const drivable_area>(std::move(pieces));
}

std::string describe_road(const drivable_area& area) {
  std::string text = "drivable area:\n";
  for (const auto& polygon : area.polygons()) {
    text += " ";
    for (const vec2 v : polygon) text += " (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ")";
    text += "\n";
  }
  return text;
}

TEST(road_constraint, the_fast_road_field_finds_exactly_the_samples_that_leave_the_road_and_their_clearances_bit_for_bit) {
  constexpr double cap = 2.0;
  std::mt19937_64 rng(testing::property_seed() + 71);
  const std::size_t count = testing::property_count(40);
  std::size_t tested = 0;
  std::size_t tested_curved = 0;
  std::size_t leaving = 0;
  std::size_t staying = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {0, false});
    in.config.resolution = trial % 2 == 0 ? sampling_resolution{7, 9} : sampling_resolution{15, 21};
    const bool curved = trial % 3 == 2;
    const auto area = curved ? random_curved_road(rng, in.ego) : random_road(rng, in.ego);
    if (!starts_on_drivable_area(*area, in.ego)) continue;
    ++tested;
    tested_curved += curved ? 1 : 0;
    const maneuver_samples samples =
        sample_maneuvers(in.ego, in.nominal.curvature, in.config.displacement_horizon, in.config.resolution);
    collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05, 0.0};
    window.time_step = std::min(window.time_step, road_time_step(in.ego, window));
    const ego_sweep sweep(in.ego, samples, window);
    road_field field(sweep, *area, cap);
    const clearance_set reference = road_clearances_reference(*area, in.ego, samples.maneuvers, window, cap);
    SCOPED_TRACE("failing input:\n" + testing::describe(in) + describe_road(*area));
    for (std::size_t m = 0; m < samples.size(); ++m) {
      ASSERT_EQ(field.collisions().test(m), !(reference[m] > 0.0)) << "sample " << m << " reference " << reference[m];
      ASSERT_EQ(field.set()[m], reference[m] > 0.0 ? cap : -cap) << "before any value is asked, sample " << m;
    }
    for (std::size_t m = 0; m < samples.size(); ++m) {
      ASSERT_EQ(field.exact(m), reference[m]) << "sample " << m;
      ASSERT_TRUE(field.is_exact(m));
      leaving += reference[m] > 0.0 ? 0 : 1;
      staying += reference[m] > 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(tested, count / 2);
  EXPECT_GT(tested_curved, count / 6);
  EXPECT_GT(leaving, 0U);
  EXPECT_GT(staying, 0U);
  std::printf("%zu roads (%zu curved): %zu samples leave the road, %zu stay on it\n", tested, tested_curved, leaving,
              staying);
}

TEST(road_constraint, a_rectangle_s_signed_distance_to_a_segment_is_that_of_the_general_convex_test_and_above_its_line_s) {
  // The rectangle's own-frame form against the separating-axis test of any convex core, on random
  // rectangles and segments: apart, crossing, inside, end-on, through corners.
  std::mt19937_64 rng(testing::property_seed() + 75);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(20000);
  std::size_t crossing = 0;
  std::size_t beside = 0;  // road edges beside the rectangle: the closed form of a line's distance
  std::size_t in_slab = 0;  // short edges beside a face, both ends in its slab: the nearer end's distance
  for (std::size_t trial = 0; trial < count; ++trial) {
    const rectangle shape{0.5 + 5.0 * unit(rng), 0.3 + 2.5 * unit(rng)};
    const placed_footprint f = place(shape, {{4.0 * unit(rng) - 2.0, 4.0 * unit(rng) - 2.0}, 7.0 * unit(rng)});
    vec2 a{8.0 * unit(rng) - 4.0, 8.0 * unit(rng) - 4.0};
    // Every fourth segment a point, every fourth through the rectangle's centre, every fourth a road's
    // edge: 40 m long, within 4 m of the centre and ending anywhere near it.
    vec2 b = trial % 4 == 0 ? a : trial % 4 == 1 ? 2.0 * f.centre - a : vec2{8.0 * unit(rng) - 4.0, 8.0 * unit(rng) - 4.0};
    if (trial % 4 == 3) {
      const vec2 e = unit_vector(7.0 * unit(rng));
      a = f.centre + (8.0 * unit(rng) - 4.0) * vec2{-e.y, e.x} - (40.0 * unit(rng) - 2.0) * e;
      b = a + 40.0 * e;
      const vec2 d = f.centre - a;
      const double h_n = f.half_length * std::abs(cross(e, f.axis)) + f.half_width * std::abs(dot(e, f.axis));
      const double h_e = f.half_length * std::abs(dot(e, f.axis)) + f.half_width * std::abs(cross(e, f.axis));
      beside += std::abs(cross(e, d)) > h_n && dot(e, d) > h_e && dot(e, d) < 40.0 - h_e ? 1 : 0;
    }
    const segment s{a, b};
    const double fast = signed_distance(f, s);
    const double reference = signed_distance_reference(f, s);
    ASSERT_EQ(signed_distance(f, segment_line(s)), fast) << "with the line computed before";
    const auto local = [&](vec2 p) { return vec2{dot(p - f.centre, f.axis), cross(f.axis, p - f.centre)}; };
    const vec2 p = local(a);
    const vec2 q = local(b);
    const auto beyond = [](double u, double v, double h) { return (u >= h && v >= h) || (u <= -h && v <= -h); };
    const auto within = [](double u, double v, double h) { return std::abs(u) <= h && std::abs(v) <= h; };
    in_slab += (within(p.x, q.x, f.half_length) && beyond(p.y, q.y, f.half_width)) ||
                       (within(p.y, q.y, f.half_width) && beyond(p.x, q.x, f.half_length))
                   ? 1
                   : 0;
    ASSERT_LE(line_distance_bound(f, segment_line(s)), reference + 1e-12 * (1.0 + std::abs(reference)))
        << "the line's bound above the distance";
    ASSERT_NEAR(fast, reference, 1e-12 * (1.0 + std::abs(reference)))
        << "rectangle " << shape.length << " x " << shape.width << " at (" << f.centre.x << ", " << f.centre.y
        << ") axis (" << f.axis.x << ", " << f.axis.y << "), segment (" << a.x << ", " << a.y << ")-(" << b.x << ", "
        << b.y << ")";
    crossing += reference < 0.0 ? 1 : 0;
  }
  EXPECT_GT(crossing, count / 10);
  EXPECT_LT(crossing, count - count / 10);
  EXPECT_GT(beside, count / 20);
  EXPECT_GT(in_slab, count / 200);
}

TEST(road_constraint, a_maneuver_proven_to_stay_on_the_road_stays_on_it_at_every_tenth_of_a_millisecond) {
  std::mt19937_64 rng(testing::property_seed() + 72);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(200);
  std::size_t proven = 0;
  std::size_t not_proven = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = testing::random_scene(rng, {0, false});
    const auto area = random_road(rng, in.ego);
    if (!starts_on_drivable_area(*area, in.ego)) continue;
    const ego_limits& limits = in.ego.limits;
    const maneuver u{-limits.max_deceleration + (limits.max_acceleration + limits.max_deceleration) * unit(rng),
                     0.3 * (unit(rng) - 0.5)};
    const collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05, 0.0};
    SCOPED_TRACE("failing input:\n" + testing::describe(in) + describe_road(*area) + "a " + std::to_string(u.acceleration) +
                 " kappa " + std::to_string(u.curvature));
    const bool stays = stays_on_drivable_area(*area, in.ego, u, window);
    const bool dense = stays_on_drivable_area_reference(*area, in.ego, u, window, 1e-4);
    if (stays) {
      EXPECT_TRUE(dense) << "proven on the road, but off it at some tenth of a millisecond";
    }
    // What the dense scan sees off the road is never proven on it; a proof may fail on a graze.
    if (!dense) {
      EXPECT_FALSE(stays);
    }
    proven += stays ? 1 : 0;
    not_proven += stays ? 0 : 1;
    // The sampled road clearance is ≤ 0 for every maneuver off the road at a sample time.
    if (!(road_clearance(*area, in.ego, u, window, 2.0) > 0.0)) {
      EXPECT_FALSE(stays);
    }
  }
  EXPECT_GT(proven, 0U);
  EXPECT_GT(not_proven, 0U);
}

TEST(road_constraint, a_proof_whose_last_step_is_cut_short_by_the_horizon_is_not_a_departure) {
  // The ego drives straight at 10 m/s towards the road's edge at an angle whose sine is 0.7: its
  // front left corner closes on the edge at 7 m/s, the largest point speed is 10 m/s, so each step
  // of the proof covers 0.7 of what is left to the contact, due 0.5 ms after T_h = 1 s. The steps
  // before T_h shrink to 1.7 ms; the last, 0.51 ms, reaches T_h and is below the resolution of 1 ms.
  ego_state ego;
  ego.speed = 10.0;
  ego.pose = {{0.0, 0.0}, std::asin(0.7)};
  const double corner = 2.25 * 0.7 + 0.9 * std::sqrt(1.0 - 0.49);
  const auto road_to = [&](double contact_time) {
    const double edge = corner + 7.0 * contact_time;
    return drivable_area(std::vector<std::vector<vec2>>{{{-100.0, -50.0}, {100.0, -50.0}, {100.0, edge}, {-100.0, edge}}});
  };
  const collision_window window{1.0, 3.0, 0.05, 0.0};
  const drivable_area clear = road_to(1.0005);
  ASSERT_TRUE(starts_on_drivable_area(clear, ego));
  EXPECT_TRUE(stays_on_drivable_area(clear, ego, {0.0, 0.0}, window, 1e-3));
  EXPECT_TRUE(stays_on_drivable_area_reference(clear, ego, {0.0, 0.0}, window, 1e-4));
  // The contact 0.5 ms before T_h instead: off the road.
  const drivable_area off = road_to(0.9995);
  EXPECT_FALSE(stays_on_drivable_area(off, ego, {0.0, 0.0}, window, 1e-3));
  EXPECT_FALSE(stays_on_drivable_area_reference(off, ego, {0.0, 0.0}, window, 1e-4));
}

TEST(road_constraint, a_road_wider_than_every_maneuver_s_reach_changes_no_index_and_no_command) {
  std::mt19937_64 rng(testing::property_seed() + 73);
  const std::size_t count = testing::property_count(20);
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {trial % 3, trial % 2 == 1});
    const plan_result without = plan(in);
    const vec2 p = in.ego.pose.position;
    in.drivable_area = std::make_shared<const drivable_area>(
        std::vector<std::vector<vec2>>{{p + vec2{-500.0, -500.0}, p + vec2{500.0, -500.0}, p + vec2{500.0, 500.0},
                                        p + vec2{-500.0, 500.0}}});
    const plan_result with = plan(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in));
    ASSERT_TRUE(with.ok() && without.ok());
    EXPECT_TRUE(with.on_drivable_area);
    EXPECT_FALSE(without.on_drivable_area);
    EXPECT_EQ(with.mi_brake, without.mi_brake);
    EXPECT_EQ(with.mi_accelerate, without.mi_accelerate);
    EXPECT_EQ(with.command.acceleration, without.command.acceleration);
    EXPECT_EQ(with.command.curvature, without.command.curvature);
    EXPECT_EQ(with.forecast_index, without.forecast_index);
    EXPECT_EQ(with.mode, without.mode);
  }
}

TEST(road_constraint, the_planner_keeps_to_the_road_and_agrees_with_the_reference_planner_within_the_accuracy_bound) {
  std::mt19937_64 rng(testing::property_seed() + 74);
  const std::size_t count = testing::property_count(16);
  std::size_t planned = 0;
  std::size_t narrowed = 0;
  double worst = 0.0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {trial % 2, false});
    in.drivable_area = random_road(rng, in.ego);
    if (!starts_on_drivable_area(*in.drivable_area, in.ego)) continue;
    ++planned;
    const plan_result fast = plan(in);
    const plan_result reference = plan_reference(in);
    SCOPED_TRACE("failing input:\n" + testing::describe(in) + describe_road(*in.drivable_area));
    ASSERT_TRUE(fast.ok() && reference.ok());
    EXPECT_TRUE(fast.on_drivable_area && reference.on_drivable_area);
    for (std::size_t i = 0; i < fast.forecast_times.size(); ++i) {
      EXPECT_NEAR(fast.mi_brake[i], reference.mi_brake[i], 0.02) << "tau " << fast.forecast_times[i];
      EXPECT_NEAR(fast.mi_accelerate[i], reference.mi_accelerate[i], 0.02) << "tau " << fast.forecast_times[i];
      worst = std::max({worst, std::abs(fast.mi_brake[i] - reference.mi_brake[i]),
                        std::abs(fast.mi_accelerate[i] - reference.mi_accelerate[i])});
    }
    narrowed += fast.mi_brake.front() < 1.0 && in.obstacles.empty() ? 1 : 0;
    // The command keeps to the road over the whole of [0, T_h] unless there was no room left.
    if (fast.mode != planning_mode::near_crash) {
      const collision_window window{in.config.displacement_horizon, in.config.collision_window, 0.05, 0.0};
      EXPECT_TRUE(stays_on_drivable_area_reference(*in.drivable_area, in.ego, fast.command, window, 1e-4))
          << "a " << fast.command.acceleration << " kappa " << fast.command.curvature;
    }
  }
  EXPECT_GT(planned, count / 2);
  EXPECT_GT(narrowed, 0U) << "some road must take room from an ego that has no obstacle";
  std::printf("largest |MI_fast - MI_reference| over %zu scenes on roads: %.4f\n", planned, worst);
}

}  // namespace
}  // namespace mm
