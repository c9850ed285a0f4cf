#include "mm/sim/scripted.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "property.hpp"

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

/// A random speed profile of 1 to 12 knots: the first at 0 or later, gaps of 10⁻⁷ s (a replayed
/// recording's speed steps) to 2 s, speeds of 0 to 20 m/s, some repeated.
speed_profile random_profile(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> knots(1, 12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  speed_profile profile;
  double time = unit(rng) < 0.5 ? 0.0 : 3.0 * unit(rng);
  double speed = 20.0 * unit(rng);
  for (int i = knots(rng); i > 0; --i) {
    profile.knots.push_back({time, speed});
    time += unit(rng) < 0.3 ? 1e-7 : 0.01 + 2.0 * unit(rng);
    if (unit(rng) < 0.7) speed = 20.0 * unit(rng);
  }
  return profile;
}

std::string describe(const speed_profile& profile) {
  std::ostringstream text;
  text.precision(17);
  for (const speed_knot& k : profile.knots) text << "(" << k.time << ", " << k.speed << ") ";
  return text.str();
}

/// Clocks to evaluate `profile` at: random ones before, over and after it, and every knot's time
/// with its neighbouring doubles.
std::vector<double> clocks_of(const speed_profile& profile, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> anywhere(-1.0, profile.knots.back().time + 2.0);
  std::vector<double> clocks;
  for (int i = 0; i < 20; ++i) clocks.push_back(anywhere(rng));
  for (const speed_knot& k : profile.knots) {
    clocks.insert(clocks.end(), {k.time, std::nextafter(k.time, -1.0), std::nextafter(k.time, 1e9), k.time - 5e-8});
  }
  return clocks;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(sim_tabulated_profile, gives_the_reference_s_speed_acceleration_and_distance_bit_for_bit) {
  std::mt19937_64 rng(mm::testing::property_seed());
  const std::size_t count = mm::testing::property_count(2000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const speed_profile profile = random_profile(rng);
    const tabulated_profile table(profile);
    for (const double clock : clocks_of(profile, rng)) {
      ASSERT_TRUE(same_bits(table.speed(clock), profile_speed(profile, clock)))
          << "speed at " << clock << " of " << describe(profile) << "(seed " << mm::testing::property_seed() << ")";
      ASSERT_TRUE(same_bits(table.acceleration(clock), profile_acceleration(profile, clock)))
          << "acceleration at " << clock << " of " << describe(profile) << "(seed " << mm::testing::property_seed() << ")";
      ASSERT_TRUE(same_bits(table.distance(clock), profile_distance(profile, clock)))
          << "distance at " << clock << " of " << describe(profile) << "(seed " << mm::testing::property_seed() << ")";
    }
  }
}

TEST(sim_prepared_script, gives_scripted_state_bit_for_bit_with_and_without_a_stop) {
  std::mt19937_64 rng(mm::testing::property_seed() + 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = mm::testing::property_count(1000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    scripted_motion m;
    m.path = straight_road(5.0 + 100.0 * unit(rng));
    m.start_time = unit(rng) < 0.5 ? 0.0 : 2.0 * unit(rng);
    m.start_arc_length = 0.5 * m.path.length() * unit(rng);
    m.before_start = unit(rng) < 0.5 ? before_start_behaviour::absent : before_start_behaviour::wait;
    m.speed = random_profile(rng);
    if (unit(rng) < 0.6) {
      const double at = m.start_arc_length + (m.path.length() - m.start_arc_length) * unit(rng);
      m.stop = stop_rule{at, unit(rng) < 0.3 ? std::nullopt : std::optional(0.1 + 3.0 * unit(rng))};
    }
    const prepared_script script(m);
    std::vector<double> times;
    for (const double clock : clocks_of(m.speed, rng)) times.push_back(m.start_time + clock);
    for (int i = 0; i < 20; ++i) times.push_back(30.0 * unit(rng));
    for (const double time : times) {
      const scripted_sample fast = script.state(time);
      const scripted_sample reference = scripted_state(m, time);
      ASSERT_TRUE(fast.phase == reference.phase && same_bits(fast.arc_length, reference.arc_length) &&
                  same_bits(fast.speed, reference.speed) && same_bits(fast.acceleration, reference.acceleration))
          << "at " << time << ": start " << m.start_time << " s at " << m.start_arc_length << " m, stop "
          << (m.stop ? m.stop->arc_length : -1.0) << " m, profile " << describe(m.speed) << "(seed "
          << mm::testing::property_seed() << ")";
    }
  }
}

}  // namespace
