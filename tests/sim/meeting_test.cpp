#include "mm/sim/meeting.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using namespace mm::sim;

TEST(sim_meeting, the_agent_that_would_arrive_earlier_is_delayed_by_the_difference) {
  // S1 of the project: A 40 m at 100/9 m/s (3.6 s), B 50 m at 10 m/s (5 s): A starts 1.4 s late.
  const std::vector<double> starts{0.0, 0.0};
  const std::vector<meeting> m{{0, 1, travel_time(40.0, 100.0 / 9.0), travel_time(50.0, 10.0), 0.0}};
  const std::vector<double> t = meeting_start_times(starts, m);
  EXPECT_NEAR(t[0], 1.4, 1e-12);
  EXPECT_EQ(t[1], 0.0);
  EXPECT_NEAR(t[0] + 3.6, t[1] + 5.0, 1e-12);  // both arrive at 5 s

  const std::vector<meeting> swapped{{1, 0, 5.0, 3.6, 0.0}};
  EXPECT_EQ(meeting_start_times(starts, swapped), t);  // the order of the two names does not matter
}

TEST(sim_meeting, a_lag_makes_the_second_agent_arrive_that_much_later) {
  const std::vector<double> starts{0.0, 0.0};
  const std::vector<meeting> m{{0, 1, 2.0, 2.0, 1.5}};
  const std::vector<double> t = meeting_start_times(starts, m);
  EXPECT_EQ(t[0], 0.0);
  EXPECT_EQ(t[1], 1.5);
  const std::vector<meeting> early{{0, 1, 2.0, 2.0, -0.5}};
  EXPECT_EQ(meeting_start_times(starts, early), (std::vector<double>{0.5, 0.0}));
}

TEST(sim_meeting, given_start_times_are_lower_bounds_and_one_of_the_group_keeps_its_own) {
  // A (0) meets B (1) and C (2); D (3) meets nobody and keeps its 7 s.
  const std::vector<double> starts{1.0, 0.0, 4.0, 7.0};
  const std::vector<meeting> m{{0, 1, 5.0, 3.0, 0.0}, {0, 2, 5.0, 1.0, 0.0}};
  const std::vector<double> t = meeting_start_times(starts, m);
  // Relative to A: B starts 2 s later, C 4 s later. C's own 4 s binds: A at 0 would put C at 4.
  // With A's own 1 s, C = 5 ≥ 4 and B = 3 ≥ 0: A keeps its start.
  EXPECT_DOUBLE_EQ(t[0], 1.0);
  EXPECT_DOUBLE_EQ(t[1], 3.0);
  EXPECT_DOUBLE_EQ(t[2], 5.0);
  EXPECT_EQ(t[3], 7.0);
  EXPECT_DOUBLE_EQ(t[0] + 5.0, t[1] + 3.0);
  EXPECT_DOUBLE_EQ(t[0] + 5.0, t[2] + 1.0);

  const std::vector<double> late_c{0.0, 0.0, 9.0};
  const std::vector<double> u = meeting_start_times(late_c, m);
  EXPECT_DOUBLE_EQ(u[2], 9.0);  // C keeps its 9 s, the others follow it
  EXPECT_DOUBLE_EQ(u[0], 5.0);
  EXPECT_DOUBLE_EQ(u[1], 7.0);
}

TEST(sim_meeting, consistent_cycles_are_accepted_and_contradictory_ones_rejected) {
  const std::vector<double> starts{0.0, 0.0, 0.0};
  const std::vector<meeting> consistent{{0, 1, 3.0, 1.0, 0.0}, {1, 2, 1.0, 2.0, 0.0}, {0, 2, 3.0, 2.0, 0.0}};
  const std::vector<double> t = meeting_start_times(starts, consistent);
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 2.0);
  EXPECT_DOUBLE_EQ(t[2], 1.0);
  const std::vector<meeting> contradictory{{0, 1, 3.0, 1.0, 0.0}, {1, 2, 1.0, 2.0, 0.0}, {0, 2, 3.0, 2.0, 0.5}};
  EXPECT_THROW(meeting_start_times(starts, contradictory), std::invalid_argument);
}

TEST(sim_meeting, invalid_meetings_are_rejected) {
  const std::vector<double> starts{0.0, 0.0};
  EXPECT_THROW(meeting_start_times(starts, std::vector<meeting>{{0, 2, 1.0, 1.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(meeting_start_times(starts, std::vector<meeting>{{1, 1, 1.0, 1.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(meeting_start_times(starts, std::vector<meeting>{{0, 1, -1.0, 1.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(travel_time(10.0, 0.0), std::invalid_argument);
  EXPECT_THROW(travel_time(-1.0, 5.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(travel_time(27.0, 35.0 / 3.6), 27.0 * 3.6 / 35.0);
}

TEST(sim_meeting, the_arc_length_of_a_point_on_a_path_is_found_and_a_point_off_it_rejected) {
  // S3's B: 16.543 m south, then a left turn on a 15 m arc; A's path x = 1.75 crosses the arc
  // after 15·asin(9.6307/15)... i.e. polar angle 180° → 219.94° about (13.25, 13.25).
  path b(mm::pose{{-1.75, 29.793}, -std::numbers::pi / 2.0});
  b.straight(16.543).turn(15.0, std::numbers::pi / 2.0).straight(50.0);
  const double dy = std::sqrt(15.0 * 15.0 - 11.5 * 11.5);
  const double swept = std::atan2(dy, 11.5);  // angle below the centre's west direction
  const double s = arc_length_at(b, {1.75, 13.25 - dy}, 1e-6);
  EXPECT_NEAR(s, 16.543 + 15.0 * swept, 1e-9);
  EXPECT_NEAR(s, 27.0, 2e-3);
  EXPECT_THROW(arc_length_at(b, {1.75, 13.25 - dy + 0.5}, 0.1), std::invalid_argument);
  EXPECT_THROW(arc_length_at(b, {-1.75, 40.0}, 0.1), std::invalid_argument);  // on the extension only
}

}  // namespace
