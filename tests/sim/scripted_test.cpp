#include "mm/sim/scripted.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace mm::sim;

path straight_road(double length) {
  path p(mm::pose{{0.0, 0.0}, 0.0});
  p.straight(length);
  return p;
}

TEST(sim_speed_profile, distances_integrate_the_piecewise_linear_speed_exactly) {
  const speed_profile brake_to_rest{{{0.0, 10.0}, {2.0, 0.0}}};  // 10 m/s to rest in 2 s: 10 m
  EXPECT_DOUBLE_EQ(profile_distance(brake_to_rest, 1.0), 7.5);
  EXPECT_DOUBLE_EQ(profile_distance(brake_to_rest, 2.0), 10.0);
  EXPECT_DOUBLE_EQ(profile_distance(brake_to_rest, 5.0), 10.0);
  EXPECT_DOUBLE_EQ(profile_speed(brake_to_rest, 0.5), 7.5);
  EXPECT_DOUBLE_EQ(profile_acceleration(brake_to_rest, 0.5), -5.0);
  EXPECT_DOUBLE_EQ(profile_acceleration(brake_to_rest, 3.0), 0.0);
  // 10x − 2.5x² = 5  ⇒  x = 2 − √2.
  EXPECT_NEAR(*profile_time_to_cover(brake_to_rest, 5.0), 2.0 - std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(*profile_time_to_cover(brake_to_rest, 10.0), 2.0, 1e-6);
  EXPECT_FALSE(profile_time_to_cover(brake_to_rest, 10.5).has_value());

  const speed_profile late_start{{{1.0, 2.0}, {3.0, 6.0}}};  // 2 m/s until 1 s, ramp to 6 m/s at 3 s
  EXPECT_DOUBLE_EQ(profile_distance(late_start, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(profile_distance(late_start, 3.0), 2.0 + 8.0);
  EXPECT_DOUBLE_EQ(profile_distance(late_start, 4.0), 2.0 + 8.0 + 6.0);
  EXPECT_DOUBLE_EQ(*profile_time_to_cover(late_start, 16.0), 4.0);
}

TEST(sim_scripted_motion, an_agent_is_absent_before_its_start_time_then_moves_from_its_start_arc_length) {
  scripted_motion m;
  m.path = straight_road(100.0);
  m.start_time = 2.0;
  m.start_arc_length = 10.0;
  m.speed = speed_profile::constant(5.0);
  EXPECT_EQ(scripted_state(m, 1.99).phase, motion_phase::not_started);
  EXPECT_DOUBLE_EQ(scripted_state(m, 1.99).arc_length, 10.0);
  const scripted_sample later = scripted_state(m, 4.0);
  EXPECT_EQ(later.phase, motion_phase::moving);
  EXPECT_DOUBLE_EQ(later.arc_length, 20.0);
  EXPECT_DOUBLE_EQ(later.speed, 5.0);
  EXPECT_EQ(scripted_state(m, 20.0).phase, motion_phase::finished);  // 10 + 5·18 ≥ 100
  EXPECT_DOUBLE_EQ(*time_to_reach(m, 60.0), 12.0);
  EXPECT_FALSE(time_to_reach(m, 5.0).has_value());
}

TEST(sim_scripted_motion, a_pedestrian_stops_at_the_kerb_for_its_duration_then_walks_on) {
  scripted_motion walk;
  walk.path = straight_road(20.0);
  walk.speed = speed_profile::constant(1.4);
  walk.stop = stop_rule{7.0, 2.0};  // reached at 5 s, stands until 7 s
  EXPECT_EQ(scripted_state(walk, 4.9).phase, motion_phase::moving);
  EXPECT_NEAR(scripted_state(walk, 4.9).arc_length, 6.86, 1e-12);
  const scripted_sample waiting = scripted_state(walk, 6.5);
  EXPECT_EQ(waiting.phase, motion_phase::stopped);
  EXPECT_DOUBLE_EQ(waiting.arc_length, 7.0);
  EXPECT_DOUBLE_EQ(waiting.speed, 0.0);
  const scripted_sample resumed = scripted_state(walk, 8.0);
  EXPECT_EQ(resumed.phase, motion_phase::moving);
  EXPECT_NEAR(resumed.arc_length, 7.0 + 1.4, 1e-12);
  EXPECT_DOUBLE_EQ(resumed.speed, 1.4);
  EXPECT_NEAR(*time_to_reach(walk, 14.0), 12.0, 1e-12);

  walk.stop->duration.reset();  // stop for ever
  EXPECT_EQ(scripted_state(walk, 1000.0).phase, motion_phase::stopped);
  EXPECT_DOUBLE_EQ(scripted_state(walk, 1000.0).arc_length, 7.0);
  EXPECT_FALSE(time_to_reach(walk, 7.5).has_value());
  EXPECT_NEAR(*time_to_reach(walk, 7.0), 5.0, 1e-12);
}

}  // namespace
