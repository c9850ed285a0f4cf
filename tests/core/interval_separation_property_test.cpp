#include "mm/interval_separation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "mm/footprint.hpp"
#include "mm/forecast.hpp"
#include "mm/maneuver.hpp"
#include "property.hpp"

namespace mm {
namespace {

constexpr double pi = std::numbers::pi;

/// An ego executing a maneuver from the origin and an obstacle following its forecast, and the
/// interval motions `separated_throughout` takes for [t_a, t_a + duration]: the bounds a
/// `clearance_field` gives it.
struct moving_pair {
  double speed;
  maneuver u;
  double horizon = 1.0;
  double speed_cap = 30.0;
  motion_estimate obstacle;
  double forecast_time;
  footprint ego_shape;
  footprint obstacle_shape;

  static support_shape support(const footprint& shape) {
    if (const auto* d = std::get_if<disc>(&shape)) return {{0.0, 0.0}, d->radius};
    const rectangle& r = std::get<rectangle>(shape);
    return {{r.length / 2.0, r.width / 2.0}, 0.0};
  }
  placement ego_at(double t) const {
    return maneuver_placement({{0.0, 0.0}, 0.0}, {1.0, 0.0}, speed, u, t, horizon, speed_cap);
  }
  placement obstacle_at(double t) const {
    const pose p = forecast_pose(obstacle, forecast_time, t);
    return {p.position, unit_vector(p.heading)};
  }
  double clearance(double t, double margin) const {
    const placement e = ego_at(t);
    const placement o = obstacle_at(t);
    return signed_distance(place(ego_shape, e.position, e.direction), place(obstacle_shape, o.position, o.direction)) -
           margin;
  }
  interval_separation separation(double from, double duration, double margin) const {
    const double top = std::max(speed, speed_after(speed, u.acceleration, horizon, speed_cap));
    const double ego_acceleration =
        from < horizon ? (std::abs(u.acceleration) + std::abs(u.curvature) * top * top) * (1.0 + 1e-9) : 0.0;
    // The headings: κ·s(t) on the arc, where s'' is a or 0, constant after the horizon; the
    // obstacle's turns at ω until τ, then not at all.
    const double to = from + duration;
    const double ego_turn = std::abs(u.curvature) * top * duration;
    const double ego_bend = to <= horizon || from >= horizon
                                ? std::abs(u.curvature) * std::abs(u.acceleration) * duration * duration / 8.0 * (1.0 + 1e-9)
                                : ego_turn;
    const double obstacle_turn = std::abs(obstacle.yaw_rate) * duration;
    const double obstacle_bend = to <= forecast_time || from >= forecast_time ? 0.0 : obstacle_turn;
    const interval_motion ego{ego_at(from), ego_at(to), ego_acceleration, ego_turn, ego_bend};
    const interval_motion other{obstacle_at(from), obstacle_at(to), obstacle.speed * std::abs(obstacle.yaw_rate),
                                obstacle_turn, obstacle_bend};
    return separated_throughout(support(ego_shape), ego, support(obstacle_shape), other, duration, margin);
  }
  std::string describe(double from, double duration, double margin) const {
    std::ostringstream out;
    out.precision(17);
    out << "ego v0 " << speed << " a " << u.acceleration << " kappa " << u.curvature << " shape (" << support(ego_shape).half.x
        << ", " << support(ego_shape).half.y << ", " << support(ego_shape).radius << "); obstacle (" << support(obstacle_shape).half.x
        << ", " << support(obstacle_shape).half.y << ", " << support(obstacle_shape).radius << ") at (" << obstacle.pose.position.x << ", " << obstacle.pose.position.y
        << ", " << obstacle.pose.heading << ") v " << obstacle.speed << " omega " << obstacle.yaw_rate << " tau "
        << forecast_time << "; interval [" << from << ", " << from + duration << "], margin " << margin;
    return out.str();
  }
};

TEST(interval_separation_property, a_direction_found_separating_two_moving_footprints_separates_them_at_every_time_between) {
  std::mt19937_64 rng(testing::property_seed() + 41);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = testing::property_count(16000);
  const double durations[] = {0.025, 0.05, 0.1, 0.2, 0.4};
  std::size_t separated = 0;
  std::size_t close = 0;  // separated with a clearance below 0.2 m somewhere in the interval
  for (std::size_t trial = 0; trial < count; ++trial) {
    moving_pair pair;
    pair.speed = 20.0 * unit(rng);
    pair.u = {-7.0 + 10.0 * unit(rng), (2.0 * unit(rng) - 1.0) / 5.5};
    // Discs too, whose supports do not grow as they turn: there only the bound on the dip tells.
    pair.ego_shape = unit(rng) < 0.5 ? footprint{disc{0.3 + 0.7 * unit(rng)}}
                                     : footprint{rectangle{3.0 + 2.5 * unit(rng), 1.5 + 0.6 * unit(rng)}};
    const bool pedestrian = unit(rng) < 0.3;
    pair.obstacle_shape =
        pedestrian ? footprint{disc{0.2 + 0.3 * unit(rng)}} : footprint{rectangle{3.0 + 2.5 * unit(rng), 1.5 + 0.6 * unit(rng)}};
    pair.obstacle.speed = (pedestrian ? 2.5 : 15.0) * unit(rng);
    pair.obstacle.yaw_rate = (pedestrian ? 0.0 : 1.6 * unit(rng) - 0.8);
    pair.forecast_time = 2.0 * unit(rng);
    const double duration = durations[rng() % 5];
    // A third of the intervals hold the time at which a heading stops turning (the ego's horizon,
    // the obstacle's forecast time): there the heading is not linear in time.
    const double kind = unit(rng);
    const double into = duration * (0.2 + 0.6 * unit(rng));
    const double from = kind < 0.17   ? std::max(0.0, pair.horizon - into)
                        : kind < 0.33 ? std::max(0.0, pair.forecast_time - into)
                                      : 2.5 * unit(rng);
    const double margin = unit(rng) < 0.5 ? 0.0 : 0.3 * unit(rng);
    pair.obstacle.pose = {{0.0, 0.0}, 2.0 * pi * unit(rng)};
    // Shifting the obstacle's start shifts its whole forecast.
    const auto put_obstacle = [&](double t, vec2 where) {
      pair.obstacle.pose.position = pair.obstacle.pose.position + (where - pair.obstacle_at(t).position);
    };
    if (unit(rng) < 0.5) {
      // Anywhere within a few metres of the ego at the interval's start.
      put_obstacle(from, pair.ego_at(from).position + vec2{8.0 * unit(rng) - 4.0, 8.0 * unit(rng) - 4.0});
    } else {
      // Grazing the ego inside the interval, where only the bound on the dip between the ends can
      // tell: at a clearance between −0.1 and 0.3 m at a time between its ends, on a random side.
      const double t = from + duration * (0.2 + 0.6 * unit(rng));
      const double target = -0.1 + 0.4 * unit(rng);
      // Half of them on the outside of the ego's turn, where its path bulges towards the obstacle.
      const placement at_t = pair.ego_at(t);
      const double outward = std::atan2(at_t.direction.y, at_t.direction.x) - (pair.u.curvature > 0.0 ? pi / 2 : -pi / 2);
      const vec2 side = unit_vector(unit(rng) < 0.5 ? outward + 0.6 * unit(rng) - 0.3 : 2.0 * pi * unit(rng));
      double inside = 0.0;
      double outside = 12.0;
      for (int step = 0; step < 60; ++step) {
        const double middle = 0.5 * (inside + outside);
        put_obstacle(t, pair.ego_at(t).position + middle * side);
        (pair.clearance(t, margin) < target ? inside : outside) = middle;
      }
      put_obstacle(t, pair.ego_at(t).position + outside * side);
    }
    const interval_separation result = pair.separation(from, duration, margin);
    if (!result.separated) continue;
    ++separated;
    const std::string input = "trial " + std::to_string(trial) + ": " + pair.describe(from, duration, margin);
    double lowest = std::numeric_limits<double>::infinity();
    constexpr int points = 400;
    for (int j = 0; j <= points; ++j) {
      const double t = from + duration * j / points;
      const double c = pair.clearance(t, margin);
      lowest = std::min(lowest, c);
      ASSERT_GT(c, 0.0) << input << " at t = " << t;
    }
    ASSERT_LE(result.gap_at_end, pair.clearance(from + duration, margin)) << input;
    if (lowest < 0.2) ++close;
  }
  // Not vacuous: it separates many, and many that pass within 0.2 m.
  EXPECT_GT(separated, count / 5);
  EXPECT_GT(close, count / 50);
}

}  // namespace
}  // namespace mm
