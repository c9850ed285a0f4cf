// `maneuvermap snapshot` on S1 without steering: the safe accelerations of the re-planned step
// are the closed form of spec §10 (paper Fig. 1), as tests/core/one_dimensional_case_test.cpp
// shows for the core on a hand-made scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "mm/cli/commands.hpp"

namespace {

using namespace mm::cli;
namespace sf = mm::scenario_file;
constexpr double car_length = 4.5;
constexpr double car_width = 1.8;

/// Spec §10 for A east along y = 0 at x_a, B south along x = 0 at y_b, with the acceleration held
/// for h = min(T_h, Δt): D = V_A Δt + a h (Δt − h/2), which is the spec's V_A Δt + a Δt²/2 when
/// T_h ≥ Δt.
struct closed_form {
  double a1 = 0.0;           ///< yield: a ≤ a1
  double a2 = 0.0;           ///< pass: a ≥ a2
  double yield_bound = 0.0;  ///< a1 corrected for the stop at zero speed
  double dt2 = 0.0;
};

closed_form solve(double x_a, double v_a, double y_b, double v_b, double horizon) {
  const double dt1 = (y_b - car_length / 2.0 - car_width / 2.0) / v_b;  // B's front reaches A's near edge
  const double dt2 = (y_b + car_length / 2.0 + car_width / 2.0) / v_b;  // B's rear clears A's far edge
  const double d_a1 = -x_a + car_width / 2.0 + car_length / 2.0;        // A's rear clears B's road
  const double d_a2 = -x_a - car_width / 2.0 - car_length / 2.0;        // A's front stays short of it
  const auto bound = [&](double distance, double dt) {
    const double h = std::min(horizon, dt);
    return (distance - v_a * dt) / (h * (dt - h / 2.0));
  };
  closed_form f;
  f.dt2 = dt2;
  f.a1 = bound(d_a2, dt2);
  f.a2 = bound(d_a1, dt1);
  const double h2 = std::min(horizon, dt2);
  // A maneuver that stops within the window covers v²/(2|a|) instead.
  f.yield_bound = f.a1 >= -v_a / h2 ? f.a1 : -v_a * v_a / (2.0 * d_a2);
  return f;
}

struct comparison {
  std::size_t checked = 0;
  std::size_t safe = 0;
  double largest_safe_brake = -1e9;
  double smallest_safe_accel = 1e9;
};

/// Compares every sample of `result` (τ index 0) with `f`; samples within `tolerance` of a bound
/// are not judged.
comparison compare(const mm::plan_result& result, const closed_form& f, double tolerance) {
  comparison c;
  const mm::sample_snapshot& s = *result.samples;
  const double yield_max = std::min(0.0, f.yield_bound);
  const double pass_min = std::max(0.0, f.a2);
  for (std::size_t m = 0; m < s.maneuvers.size(); ++m) {
    if (s.on_nominal_curvature[m]) continue;
    const double a = s.maneuvers[m].acceleration;
    EXPECT_EQ(s.maneuvers[m].curvature, 0.0);
    const bool brake = s.families[m] == mm::family::brake;
    const bool safe = s.safe_by_forecast[0][m] != 0;
    const bool expected = brake ? (a <= yield_max || a >= f.a2) : (a >= pass_min || a <= f.yield_bound);
    const double to_bound = brake ? std::min(std::abs(a - yield_max), std::abs(a - f.a2))
                                  : std::min(std::abs(a - pass_min), std::abs(a - f.yield_bound));
    if (to_bound > tolerance) {
      EXPECT_EQ(safe, expected) << (brake ? "brake" : "accelerate") << " a = " << a << ", a1 = " << f.a1
                                << ", yield bound = " << f.yield_bound << ", a2 = " << f.a2;
      ++c.checked;
    }
    if (safe) {
      ++c.safe;
      if (brake) c.largest_safe_brake = std::max(c.largest_safe_brake, a);
      else c.smallest_safe_accel = std::min(c.smallest_safe_accel, a);
    }
  }
  return c;
}

/// The scene of the snapshot: A's position and speed, B's observed position and speed.
closed_form scene_of(const snapshot& shot) {
  const mm::plan_input& in = shot.input;
  EXPECT_EQ(in.ego.pose.position.y, 0.0);  // no steering: A stays on its line
  EXPECT_EQ(in.obstacles.size(), 1U);
  const mm::observation& b = in.obstacles.at(0).history.back();
  EXPECT_NEAR(b.pose.position.x, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(b.time, shot.time);
  return solve(in.ego.pose.position.x, in.ego.speed, b.pose.position.y, b.speed, in.config.displacement_horizon);
}

class s1_closed_form : public ::testing::TestWithParam<double> {};

TEST_P(s1_closed_form, the_snapshot_s_safe_accelerations_match_spec_10_within_the_resolution) {
  // GetParam(): A's displacement horizon T_h. With T_h = T_c = 3 s the acceleration is held over
  // the whole window: the spec's closed form exactly. With the default 1 s, its generalisation.
  sf::load_options options;
  options.overrides = {{"horizon_s", GetParam()}, {"margin_m", 0.0}};
  const sf::loaded_scenario loaded = sf::load("s1-crossing-no-steering", options);
  // 3.0 s: B appeared at 1.8 s, 36 m north of the crossing; it is now 24 m away and its rear
  // clears A's road within the 3 s collision window.
  const snapshot shot = take_snapshot(loaded, "A", 3.0, 0.0);
  ASSERT_TRUE(shot.result.samples.has_value());
  const closed_form f = scene_of(shot);
  ASSERT_LT(f.dt2, shot.input.config.collision_window);

  // 1. The snapshot itself, at the scenario's resolution: 11 accelerations per family, so a
  //    bound is known to one grid step (0.7 m/s² braking, 0.3 m/s² accelerating), plus what the
  //    50 ms collision sampling can shift it (about 0.1 m/s² here).
  const double brake_step = loaded.scenario.planning_vehicles[0].limits.max_deceleration / 10.0;
  const comparison coarse = compare(shot.result, f, brake_step + 0.15);
  EXPECT_GT(coarse.checked, 10U);
  EXPECT_GT(coarse.safe, 0U);
  ASSERT_EQ(shot.rows.size(), shot.result.samples->maneuvers.size());  // --tau 0: one τ
  for (std::size_t m = 0; m < shot.rows.size(); ++m) {
    EXPECT_EQ(shot.rows[m].safe, shot.result.samples->safe_by_forecast[0][m] != 0);
  }

  // 2. The same input re-planned finely (141 accelerations, 2 ms collision steps): the bounds
  //    to 1.5 steps (0.075 m/s²) plus 0.05 m/s² of time sampling.
  mm::plan_input fine = shot.input;
  fine.config.resolution = {141, 1};
  fine.config.max_time_step = 0.002;
  fine.config.forecast_count = 1;  // B drives straight: every τ is the same forecast
  const mm::plan_result refined = mm::plan(fine);
  ASSERT_TRUE(refined.ok()) << refined.error;
  const double tolerance = 1.5 * (loaded.scenario.planning_vehicles[0].limits.max_deceleration / 140.0) + 0.05;
  const comparison c = compare(refined, f, tolerance);
  EXPECT_GT(c.checked, 250U);
  const mm::ego_limits& limits = fine.ego.limits;
  if (f.yield_bound >= -limits.max_deceleration) {
    EXPECT_NEAR(c.largest_safe_brake, std::min(0.0, f.yield_bound), tolerance) << "brake family: [−d_max, min(0, a1)]";
  } else {
    EXPECT_EQ(c.largest_safe_brake, -1e9) << "braking cannot avoid B";
  }
  if (f.a2 <= limits.max_acceleration) {
    EXPECT_NEAR(c.smallest_safe_accel, std::max(0.0, f.a2), tolerance) << "accelerate family: [max(0, a2), a_max]";
  } else {
    EXPECT_EQ(c.smallest_safe_accel, 1e9) << "accelerating cannot avoid B";
  }
}

INSTANTIATE_TEST_SUITE_P(horizons, s1_closed_form, ::testing::Values(3.0, 1.0),
                         [](const ::testing::TestParamInfo<double>& p) {
                           return p.param == 3.0 ? std::string("held_over_the_window") : std::string("default_horizon");
                         });

TEST(snapshot, the_csv_has_one_row_per_sample_and_forecast_time) {
  const sf::loaded_scenario loaded = sf::load("s1-crossing");
  const snapshot shot = take_snapshot(loaded, "A", 0.5, std::nullopt);
  EXPECT_DOUBLE_EQ(shot.time, 0.5);
  const std::size_t samples = shot.result.samples->maneuvers.size();
  EXPECT_EQ(shot.rows.size(), 17U * samples);
  std::ostringstream out;
  write_snapshot_csv(out, shot);
  const std::string text = out.str();
  EXPECT_EQ(text.rfind("tau,family,accel,curvature,end_x,end_y,area_weight,safe,selected\n", 0), 0U);
  EXPECT_EQ(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')), 1U + 17U * samples);
  EXPECT_NE(text.find("\n2.000000,accelerate,"), std::string::npos);  // the last τ
}

TEST(snapshot, the_selected_column_is_the_decision_s_set_under_adj_and_under_the_robust_policy) {
  // A turning car, under ADJ (one obstacle: the column of τ̄) and under the robust policy (every
  // forecast time TTC leaves: the intersection of those columns).
  sf::load_options options;
  options.overrides = {{"a_kmh", 40.0}, {"b_kmh", 35.0}};
  const std::string file = std::string(MM_SOURCE_DIR) + "/sweeps/s3-variants/s3-left-turn-offset-14m.yaml";
  for (const char* policy : {"adj", "robust"}) {
    options.policy = sf::parse_policy(policy);
    const snapshot shot = take_snapshot(sf::load(file, options), "A", 2.5, std::nullopt);
    const mm::plan_result& r = shot.result;
    const std::size_t samples = r.samples->maneuvers.size();
    ASSERT_EQ(shot.rows.size(), r.forecast_times.size() * samples);
    EXPECT_EQ(r.robust, std::string(policy) == "robust");
    std::size_t differ = 0;
    for (std::size_t m = 0; m < samples; ++m) {
      bool under_every = true;
      for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
        const snapshot_row& row = shot.rows[i * samples + m];
        EXPECT_EQ(row.selected, shot.rows[m].selected) << "the same in every row of sample " << m;
        if (r.excluded[i] == 0) under_every = under_every && row.safe;
      }
      const bool expected = r.robust ? under_every : shot.rows[r.forecast_index * samples + m].safe;
      EXPECT_EQ(shot.rows[m].selected, expected) << policy << ", sample " << m;
      differ += shot.rows[m].selected == shot.rows[r.forecast_index * samples + m].safe ? 0 : 1;
    }
    if (r.robust) {
      EXPECT_GT(differ, 10U) << "the robust set must differ from the column of τ̄ here";
    }
  }
}

TEST(snapshot, bad_requests_are_input_errors) {
  const sf::loaded_scenario loaded = sf::load("s1-crossing");
  EXPECT_THROW(take_snapshot(loaded, "A", 8.5, std::nullopt), input_error);   // beyond the duration
  EXPECT_THROW(take_snapshot(loaded, "A", -1.0, std::nullopt), input_error);
  EXPECT_THROW(take_snapshot(loaded, "Z", 0.5, std::nullopt), input_error);   // no such agent
  EXPECT_THROW(take_snapshot(loaded, "B", 0.5, std::nullopt), input_error);   // not a planning vehicle
  EXPECT_THROW(take_snapshot(loaded, "A", 0.2, 0.3), input_error);            // τ off the grid
  sf::load_options naive;
  naive.overrides = {{"avoid", 0.0}};
  try {
    take_snapshot(sf::load("s1-crossing", naive), "A", 7.0, std::nullopt);  // it crashed at 5.12 s
    FAIL();
  } catch (const input_error& e) {
    EXPECT_NE(std::string(e.what()).find("the run ended at t = 5.120 s"), std::string::npos) << e.what();
  }
}

}  // namespace
