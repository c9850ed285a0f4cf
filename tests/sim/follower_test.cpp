#include "mm/sim/follower.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "mm/sim/simulation.hpp"
#include "sim/scenarios.hpp"

namespace {

using namespace mm::sim;
using mm::sim::testing::cruising;
using mm::sim::testing::straight_path;
constexpr double pi = std::numbers::pi;

TEST(sim_follower, pure_pursuit_steers_on_the_circle_through_the_goal) {
  const mm::pose vehicle{{0.0, 0.0}, 0.0};
  EXPECT_DOUBLE_EQ(pure_pursuit_curvature(vehicle, {10.0, 0.0}), 0.0);
  // A goal on the circle of radius 25 tangent to the heading, centre (0, 25).
  const double angle = 0.4;
  const mm::vec2 goal{25.0 * std::sin(angle), 25.0 - 25.0 * std::cos(angle)};
  EXPECT_NEAR(pure_pursuit_curvature(vehicle, goal), 1.0 / 25.0, 1e-12);
  EXPECT_NEAR(pure_pursuit_curvature(vehicle, {goal.x, -goal.y}), -1.0 / 25.0, 1e-12);
  EXPECT_DOUBLE_EQ(lookahead_distance(2.0, follower_config{}), 5.0);
  EXPECT_DOUBLE_EQ(lookahead_distance(20.0, follower_config{}), 16.0);
}

TEST(sim_follower, the_curve_speed_limit_is_the_braking_profile_to_the_curve_speed) {
  path p(mm::pose{{0.0, 0.0}, 0.0});
  p.straight(50.0).turn(20.0, pi / 2.0);
  // v_c = √(5 · 20) = 10 m/s; 30 m before the curve: √(100 + 2·2·30) = √220.
  const curve_speed_limit ahead = curve_speed_limit_ahead(p, 20.0, 100.0, 5.0, 2.0);
  EXPECT_NEAR(ahead.curve_speed, 10.0, 1e-12);
  EXPECT_NEAR(ahead.distance, 30.0, 1e-12);
  EXPECT_NEAR(ahead.speed, std::sqrt(220.0), 1e-12);
  EXPECT_TRUE(std::isinf(curve_speed_limit_ahead(p, 20.0, 29.0, 5.0, 2.0).speed));  // beyond the preview
  EXPECT_NEAR(curve_speed_limit_ahead(p, 60.0, 10.0, 5.0, 2.0).speed, 10.0, 1e-12);  // on the curve
}

/// Runs `s` and returns the largest |lateral offset| of vehicle 0 while `window(t)` holds.
template <typename Window>
double largest_offset(scenario s, Window window) {
  simulation sim(std::move(s));
  double worst = 0.0;
  run(sim, [&](const simulation& now) {
    if (window(now.time())) worst = std::max(worst, std::abs(now.state(0).lateral_offset));
  });
  return worst;
}

TEST(sim_follower, pure_pursuit_holds_a_circle_of_radius_25_m_at_10_m_s) {
  // 30 m of straight road joining, tangentially, 3/4 of a circle of radius 25 m about the origin.
  path p(mm::pose{{-30.0, -25.0}, 0.0});
  p.straight(30.0).turn(25.0, 1.5 * pi);
  scenario s;
  s.duration = 14.0;  // the arc ends at 3 + 11.78 s
  s.planning_vehicles.push_back(cruising("A", p, 10.0));
  // Steady state: from 6 s after entering the arc (at 3 s) until the lookahead passes its end.
  // (For a unicycle, pure pursuit's steady state on a circle is the circle itself.)
  const double steady = largest_offset(s, [](double t) { return t >= 9.0 && t <= 13.5; });
  const double transient = largest_offset(s, [](double) { return true; });
  std::printf("circle R = 25 m at 10 m/s: steady |offset| <= %.5f m, with the entry transient %.4f m\n", steady,
              transient);
  EXPECT_LT(steady, 0.001);
  EXPECT_LT(transient, 0.3);  // cutting inside where the curvature jumps from 0 to 1/25
}

TEST(sim_follower, keeps_the_desired_speed_with_a_first_order_response) {
  scenario s;
  s.duration = 8.0;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 500.0), 8.0);
  a.desired_speed = 12.0;
  s.planning_vehicles.push_back(a);
  simulation sim(s);
  double fastest = 0.0;
  double at_one_second = 0.0;
  run(sim, [&](const simulation& now) {
    fastest = std::max(fastest, now.state(0).speed);
    if (now.step_index() == 100) at_one_second = now.state(0).speed;
  });
  // a = min(a_max, k_v·(v_des − v)) with k_v = 1/s: capped at 3 m/s² up to 9 m/s (1/3 s), then
  // v = 12 − 3·exp(−(t − 1/3)), time constant 1 s.
  const double expected = 12.0 - 3.0 * std::exp(-(1.0 - 1.0 / 3.0));
  EXPECT_NEAR(at_one_second, expected, 0.01);  // the command is held over each 10 ms step
  EXPECT_NEAR(sim.state(0).speed, 12.0, 0.005);
  EXPECT_LE(fastest, 12.0 + 1e-9);
}

TEST(sim_follower, slows_ahead_of_a_curve_so_that_v_squared_kappa_stays_within_a_lat_max) {
  // 80 m of straight road at 15 m/s, then a curve of radius 15 m: v_c = √(5 · 15) ≈ 8.66 m/s.
  path p(mm::pose{{0.0, 0.0}, 0.0});
  p.straight(80.0).turn(15.0, pi).straight(100.0);
  scenario s;
  s.duration = 16.0;
  s.planning_vehicles.push_back(cruising("A", p, 15.0));
  simulation sim(s);
  double worst_lateral = 0.0;
  double entry_speed = 0.0;
  double hardest_braking = 0.0;
  run(sim, [&](const simulation& now) {
    const agent_state& a = now.state(0);
    if (a.arc_length >= 80.0 && a.arc_length <= 80.0 + 15.0 * pi) {
      if (entry_speed == 0.0) entry_speed = a.speed;
      worst_lateral = std::max(worst_lateral, a.speed * a.speed / 15.0);
    }
    hardest_braking = std::min(hardest_braking, a.acceleration);
  });
  std::printf("curve R = 15 m from 15 m/s: entry %.3f m/s, max v²κ %.3f m/s², hardest braking %.3f m/s²\n",
              entry_speed, worst_lateral, hardest_braking);
  EXPECT_LE(entry_speed, std::sqrt(75.0) + 0.05);
  EXPECT_LE(worst_lateral, 5.0 * 1.01);
  EXPECT_GE(hardest_braking, -2.6);  // about the comfortable 2 m/s², far from d_max = 7 m/s²
  EXPECT_GT(sim.state(0).speed, 14.0);  // back up to speed on the straight after the curve
}

TEST(sim_follower, returns_to_its_path_from_a_lateral_offset) {
  scenario s;
  s.duration = 6.0;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 200.0), 10.0);
  a.start_lateral_offset = 2.0;
  s.planning_vehicles.push_back(a);
  simulation sim(s);
  double overshoot = 0.0;
  run(sim, [&](const simulation& now) { overshoot = std::min(overshoot, now.state(0).lateral_offset); });
  std::printf("from 2 m left: offset after 6 s %.5f m, overshoot %.5f m\n", sim.state(0).lateral_offset, overshoot);
  EXPECT_LT(std::abs(sim.state(0).lateral_offset), 0.01);
  // Linearised on a straight line, pure pursuit is e'' + (2v/L)e' + (2v²/L²)e = 0: damping ratio
  // 1/√2 whatever v and L, so an overshoot of exp(−π) ≈ 4.3 % of the initial offset.
  EXPECT_GT(overshoot, -0.05 * 2.0);
  EXPECT_LT(overshoot, -0.03 * 2.0);
}

}  // namespace

namespace {

TEST(sim_follower, car_following_allows_no_acceleration_at_the_desired_gap_less_within_it_and_more_beyond) {
  const car_following_config c{1.0, 2.0, 1.75};
  // s* = s0 + v·T at equal speeds: 2 + 10·1 = 12 m.
  EXPECT_NEAR(car_following_acceleration(10.0, {12.0, 10.0}, c, 3.0, 2.0), 0.0, 1e-12);
  EXPECT_NEAR(car_following_acceleration(10.0, {6.0, 10.0}, c, 3.0, 2.0), 3.0 * (1.0 - 4.0), 1e-12);
  EXPECT_NEAR(car_following_acceleration(10.0, {24.0, 10.0}, c, 3.0, 2.0), 3.0 * (1.0 - 0.25), 1e-12);
  // Closing at 4 m/s adds v·Δv / (2√(ab)) = 10·4 / (2√6) to the desired gap.
  const double closing_gap = 12.0 + 40.0 / (2.0 * std::sqrt(6.0));
  EXPECT_NEAR(car_following_acceleration(10.0, {closing_gap, 6.0}, c, 3.0, 2.0), 0.0, 1e-12);
  // Opening fast enough never shrinks the desired gap below the jam distance.
  EXPECT_NEAR(car_following_acceleration(0.0, {2.0, 5.0}, c, 3.0, 2.0), 0.0, 1e-12);
  EXPECT_EQ(car_following_acceleration(10.0, {0.0, 10.0}, c, 3.0, 2.0), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(car_following_acceleration(10.0, {-0.5, 10.0}, c, 3.0, 2.0), -std::numeric_limits<double>::infinity());
}

/// Smallest bumper-to-bumper gap of A behind B (both 4.5 m long, B ahead on the same line) over a run
/// of `seconds`, and the gap at its end [m].
struct following_gaps {
  double smallest = std::numeric_limits<double>::infinity();
  double last = 0.0;
};

following_gaps follow_slower_vehicle(const std::optional<car_following_config>& following, double seconds) {
  scenario s;
  s.duration = seconds;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 600.0), 60.0 / 3.6);
  a.planner.safety_margin = 0.3;
  a.follower.car_following = following;
  s.planning_vehicles.push_back(a);
  s.scripted_vehicles.push_back(
      mm::sim::testing::scripted("B", straight_path({30.0, 0.0}, 0.0, 600.0), 30.0 / 3.6));
  simulation sim(s);
  following_gaps gaps;
  run(sim, [&](const simulation& now) {
    const double gap = now.state(1).pose.position.x - now.state(0).pose.position.x - 4.5;
    gaps.smallest = std::min(gaps.smallest, gap);
    gaps.last = gap;
  });
  EXPECT_TRUE(sim.crashes().empty());
  return gaps;
}

TEST(sim_follower, with_car_following_a_faster_vehicle_settles_a_time_gap_behind_a_slower_one) {
  const double seconds = mm::sim::testing::sanitize_scale() ? 12.0 : 20.0;
  // B at 30 km/h: s* = 2 m + 8.33 m/s · 1 s = 10.33 m.
  const double desired = 2.0 + 30.0 / 3.6 * 1.0;
  const following_gaps kept = follow_slower_vehicle(car_following_config{1.0, 2.0, 1.75}, seconds);
  EXPECT_NEAR(kept.last, desired, 0.05);
  EXPECT_GT(kept.smallest, desired - 0.05);
  // Without it u_nom holds 60 km/h: the planner keeps A off B (no crash), and A does not stay
  // behind it but swerves round it and passes.
  const following_gaps passed = follow_slower_vehicle(std::nullopt, seconds);
  EXPECT_LT(passed.last, -10.0);
  std::printf("bumper gap behind B at 30 km/h: %.3f m with car following (s* = %.3f m); without, A ends %.1f m "
              "ahead of B's rear\n",
              kept.last, desired, -passed.last);
}

TEST(sim_follower, car_following_follows_the_road_user_ahead_in_the_corridor_not_beside_behind_across_or_static) {
  // A at its desired 15 m/s; B in the next lane (3.5 m beside the path) 12 m ahead, C 20 m behind,
  // D crossing A's path 15 m ahead, the static obstacle F on it 40 m ahead: none is followed, u_nom
  // keeps the speed. E, 25 m ahead in A's
  // lane at 5 m/s, is: the desired gap 2 + 15 + 15·10/(2√6) = 47.6 m exceeds E's 20.5 m.
  const auto nominal_acceleration = [](bool with_e) {
    scenario s;
    s.duration = 1.0;
    planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 300.0), 15.0);
    a.follower.car_following = car_following_config{};
    s.planning_vehicles.push_back(a);
    s.scripted_vehicles.push_back(mm::sim::testing::scripted("B", straight_path({12.0, 3.5}, 0.0, 300.0), 5.0));
    s.scripted_vehicles.push_back(mm::sim::testing::scripted("C", straight_path({-20.0, 0.0}, 0.0, 300.0), 5.0));
    s.scripted_vehicles.push_back(
        mm::sim::testing::scripted("D", straight_path({15.0, 30.0}, -pi / 2.0, 300.0), 5.0));
    s.static_obstacles.push_back({"F", {{40.0, -0.9}, {44.0, -0.9}, {44.0, 0.9}, {40.0, 0.9}}});
    if (with_e) {
      s.scripted_vehicles.push_back(mm::sim::testing::scripted("E", straight_path({25.0, 0.0}, 0.0, 300.0), 5.0));
    }
    const simulation sim(s);
    return sim.planning_input(0).value().nominal.acceleration;
  };
  EXPECT_EQ(nominal_acceleration(false), 0.0);
  const double gap = 25.0 - 4.5;
  const double desired = 2.0 + 15.0 + 15.0 * 10.0 / (2.0 * std::sqrt(3.0 * 2.0));
  EXPECT_NEAR(nominal_acceleration(true), std::max(-7.0, 3.0 * (1.0 - (desired / gap) * (desired / gap))), 1e-9);
}

TEST(sim_follower, a_lagging_scripted_vehicle_closes_on_its_script_within_its_limits_and_under_the_cap) {
  const scripted_car_following k{};  // k_v = 1/s, a_max = 3, d_max = 7
  scripted_sample script;
  script.phase = motion_phase::moving;
  script.arc_length = 14.0;
  script.speed = 6.0;
  script.acceleration = 0.5;
  // a_script + k_v·(v_script − v) + k_v²·(s_script − s): 0.5 + 1 + 1 = 2.5 at s = 13 m and v = 5 m/s; the
  // spring pulls back one that would be ahead (a run never lets it be): 0.5 + 1 − 2 = −0.5 at s = 16 m.
  EXPECT_DOUBLE_EQ(lagging_acceleration(13.0, 5.0, script, std::numeric_limits<double>::infinity(), k), 2.5);
  EXPECT_DOUBLE_EQ(lagging_acceleration(16.0, 5.0, script, std::numeric_limits<double>::infinity(), k), -0.5);
  // On the script it takes the script's acceleration.
  EXPECT_DOUBLE_EQ(lagging_acceleration(14.0, 6.0, script, std::numeric_limits<double>::infinity(), k), 0.5);
  // Far behind: at most a_max; a leader caps it; a gap closed brakes at d_max.
  EXPECT_DOUBLE_EQ(lagging_acceleration(0.0, 5.0, script, std::numeric_limits<double>::infinity(), k), 3.0);
  EXPECT_DOUBLE_EQ(lagging_acceleration(0.0, 5.0, script, -1.25, k), -1.25);
  EXPECT_DOUBLE_EQ(lagging_acceleration(0.0, 5.0, script, -std::numeric_limits<double>::infinity(), k), -7.0);
}

/// C, a scripted vehicle at 10 m/s (or along `profile`), behind A, a planning vehicle that drives
/// without avoidance along the same line from 50 m ahead and stands until it starts at `a_leaves`
/// [s] (never when infinite): the smallest bumper gap of C behind A, C's last state, and whether C
/// was ever ahead of its script or C and A crashed.
struct behind_a_standing_vehicle {
  double smallest_gap = std::numeric_limits<double>::infinity();
  double largest_lag = 0.0;  ///< how far C fell behind its script [m]
  bool ahead_of_script = false;
  bool crashed = false;
  agent_state last;
  scripted_sample last_script;
};

behind_a_standing_vehicle follow_a_standing_vehicle(const std::optional<scripted_car_following>& following,
                                                    double a_leaves, const std::optional<stop_rule>& stop,
                                                    double seconds) {
  scenario s;
  s.duration = seconds;
  planning_vehicle a = cruising("A", straight_path({50.0, 0.0}, 0.0, 1000.0), 0.0);
  a.avoidance = false;
  if (std::isfinite(a_leaves)) a.desired_speed_profile = speed_profile{{{0.0, 0.0}, {a_leaves, 0.0}, {a_leaves + 2.0, 15.0}}};
  s.planning_vehicles.push_back(a);
  scripted_vehicle c = mm::sim::testing::scripted("C", straight_path({0.0, 0.0}, 0.0, 1000.0), 10.0);
  c.motion.stop = stop;
  c.car_following = following;
  s.scripted_vehicles.push_back(c);
  simulation sim(s);
  behind_a_standing_vehicle seen;
  run(sim, [&](const simulation& now) {
    const agent_state& own = now.state(1);
    const scripted_sample script = scripted_state(now.definition().scripted_vehicles[0].motion, now.time());
    seen.smallest_gap = std::min(seen.smallest_gap, now.state(0).pose.position.x - own.pose.position.x - 4.5);
    seen.largest_lag = std::max(seen.largest_lag, script.arc_length - own.arc_length);
    seen.ahead_of_script = seen.ahead_of_script || own.arc_length > script.arc_length;
    seen.last = own;
    seen.last_script = script;
  });
  seen.crashed = !sim.crashes().empty();
  return seen;
}

TEST(sim_follower, a_scripted_vehicle_with_car_following_stops_behind_a_standing_one_that_it_runs_into_without) {
  const double seconds = mm::sim::testing::sanitize_scale() ? 15.0 : 20.0;
  const behind_a_standing_vehicle kept =
      follow_a_standing_vehicle(scripted_car_following{}, std::numeric_limits<double>::infinity(), std::nullopt, seconds);
  EXPECT_FALSE(kept.crashed);
  EXPECT_FALSE(kept.ahead_of_script);
  // IDM settles at the jam distance s0 = 2 m as it comes to rest.
  EXPECT_GT(kept.smallest_gap, 1.95);
  EXPECT_LT(kept.last.pose.position.x, 50.0 - 4.5 - 1.95);
  EXPECT_LT(kept.last.speed, 0.3);
  EXPECT_EQ(kept.last.status, agent_status::active);
  const behind_a_standing_vehicle replayed =
      follow_a_standing_vehicle(std::nullopt, std::numeric_limits<double>::infinity(), std::nullopt, seconds);
  EXPECT_TRUE(replayed.crashed);
  std::printf("C behind a standing vehicle: smallest bumper gap %.3f m, speed at %.0f s %.3f m/s; without car "
              "following it runs into it\n",
              kept.smallest_gap, seconds, kept.last.speed);
}

TEST(sim_follower, a_lagging_scripted_vehicle_catches_up_with_its_script_and_keeps_to_it_again) {
  // A stands for 4 s, then drives off at 15 m/s; C, held up behind it, catches up with its script,
  // which stops for ever at 150 m, and ends exactly where the script does.
  const behind_a_standing_vehicle seen =
      follow_a_standing_vehicle(scripted_car_following{}, 4.0, stop_rule{150.0, std::nullopt}, 25.0);
  EXPECT_FALSE(seen.crashed);
  EXPECT_FALSE(seen.ahead_of_script);
  EXPECT_GT(seen.largest_lag, 5.0);
  EXPECT_EQ(seen.last.status, agent_status::stopped);
  EXPECT_EQ(seen.last.arc_length, seen.last_script.arc_length);
  EXPECT_EQ(seen.last.arc_length, 150.0);
  std::printf("C held up by up to %.2f m behind its script, then on it again at its stop\n", seen.largest_lag);
}

TEST(sim_follower, a_scripted_vehicle_with_nothing_to_follow_keeps_to_its_script_bit_for_bit) {
  // B accelerates, brakes and stops on its way; A drives in the next lane, D crosses B's path ahead
  // of it: nothing B would follow. Every state of every agent is the same with and without B's car
  // following.
  const auto states_of = [](bool following) {
    scenario s;
    s.duration = 8.0;
    s.planning_vehicles.push_back(cruising("A", straight_path({20.0, 3.5}, 0.0, 400.0), 12.0));
    scripted_vehicle b = mm::sim::testing::scripted("B", straight_path({0.0, 0.0}, 0.0, 400.0), 0.0);
    b.motion.speed = speed_profile{{{0.0, 8.0}, {2.0, 14.0}, {4.0, 6.0}}};
    b.motion.stop = stop_rule{60.0, 1.0};
    if (following) b.car_following = scripted_car_following{};
    s.scripted_vehicles.push_back(b);
    s.scripted_vehicles.push_back(mm::sim::testing::scripted("D", straight_path({70.0, 40.0}, -pi / 2.0, 400.0), 8.0));
    simulation sim(s);
    std::vector<agent_state> all;
    run(sim, [&](const simulation& now) { all.insert(all.end(), now.states().begin(), now.states().end()); });
    return all;
  };
  const std::vector<agent_state> with = states_of(true);
  const std::vector<agent_state> without = states_of(false);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    ASSERT_EQ(with[i].pose.position.x, without[i].pose.position.x) << "state " << i;
    ASSERT_EQ(with[i].pose.position.y, without[i].pose.position.y) << "state " << i;
    ASSERT_EQ(with[i].speed, without[i].speed) << "state " << i;
    ASSERT_EQ(with[i].status, without[i].status) << "state " << i;
  }
}

TEST(sim_follower, a_scripted_vehicle_that_follows_only_road_users_off_their_scripts_leaves_the_scripts_as_they_are) {
  // C at 10 m/s 30 m behind B at 5 m/s, both scripted on one line: following whatever is ahead, C
  // is held up behind B; following only road users off their scripts, C keeps to its script (the
  // scripts' meeting is theirs to have, as in a recording).
  const auto c_lags = [](bool follows_scripted) {
    scenario s;
    s.duration = 8.0;
    s.scripted_vehicles.push_back(mm::sim::testing::scripted("B", straight_path({30.0, 0.0}, 0.0, 300.0), 5.0));
    scripted_vehicle c = mm::sim::testing::scripted("C", straight_path({0.0, 0.0}, 0.0, 300.0), 10.0);
    c.car_following = scripted_car_following{};
    c.car_following->follows_scripted = follows_scripted;
    s.scripted_vehicles.push_back(c);
    simulation sim(s);
    double lag = 0.0;
    run(sim, [&](const simulation& now) {
      lag = std::max(lag, scripted_state(now.definition().scripted_vehicles[1].motion, now.time()).arc_length -
                              now.state(1).arc_length);
    });
    return lag;
  };
  EXPECT_GT(c_lags(true), 5.0);
  EXPECT_EQ(c_lags(false), 0.0);

  // A stands at 100 m; B (from 50 m) and C (from 20 m) drive at 10 m/s behind it, following only road
  // users off their scripts: B is held up behind A, and C, behind B, in turn.
  scenario s;
  s.duration = 15.0;
  planning_vehicle a = cruising("A", straight_path({100.0, 0.0}, 0.0, 1000.0), 0.0);
  a.avoidance = false;
  s.planning_vehicles.push_back(a);
  for (const auto& [name, x] : {std::pair{"B", 50.0}, std::pair{"C", 20.0}}) {
    scripted_vehicle v = mm::sim::testing::scripted(name, straight_path({x, 0.0}, 0.0, 1000.0), 10.0);
    v.car_following = scripted_car_following{};
    v.car_following->follows_scripted = false;
    s.scripted_vehicles.push_back(v);
  }
  simulation sim(s);
  double a_to_b = std::numeric_limits<double>::infinity();
  double b_to_c = std::numeric_limits<double>::infinity();
  run(sim, [&](const simulation& now) {
    a_to_b = std::min(a_to_b, now.state(0).pose.position.x - now.state(1).pose.position.x - 4.5);
    b_to_c = std::min(b_to_c, now.state(1).pose.position.x - now.state(2).pose.position.x - 4.5);
  });
  EXPECT_TRUE(sim.crashes().empty());
  EXPECT_GT(a_to_b, 1.9);
  EXPECT_GT(b_to_c, 1.9);
  EXPECT_LT(sim.state(2).speed, 0.5) << "C stops behind B";
}

}  // namespace
