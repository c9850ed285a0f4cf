// libFuzzer target for the planner (mm::plan): the bytes are decoded into a planning input — the
// ego, its limits and nominal maneuver, up to four obstacles with noisy histories or given motion
// estimates, every field of the configuration at a small resolution, sometimes a drivable area —
// mostly within the ranges the planner takes, sometimes at their ends, 0, NaN, ±inf or an arbitrary
// double. Whatever the input, the planner must refuse it with a status and a message, or plan it
// with a finite command within the ego's limits, every index in [0, 1], the map column's sizes as
// configured and a TTC that is not NaN. Each input is planned for up to four steps (the same scene
// later, sometimes at another speed, footprint or resolution, or another scene) by one kept
// mm::planner, which must give mm::plan's result bit for bit: its cache must never carry one step
// into another's result.
// A crash, a hang, an exception, a leak or undefined behaviour is a bug.
// Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "mm/drivable_area.hpp"
#include "mm/planner.hpp"

namespace {

/// Decodes a planning input from the fuzzer's bytes.
class decoder {
 public:
  decoder(const std::uint8_t* data, std::size_t size) : bytes_(data, size) {}

  /// Mostly a number in [lo, hi]; sometimes an end, 0, NaN, ±inf or any double.
  double number(double lo, double hi) {
    const auto selector = bytes_.ConsumeIntegral<std::uint8_t>();
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) return lo;  // a range from a decoded end
    if (selector < 240) return bytes_.ConsumeFloatingPointInRange(lo, hi);
    switch (selector) {
      case 240: return lo;
      case 241: return hi;
      case 242: return 0.0;
      case 243: return std::numeric_limits<double>::quiet_NaN();
      case 244: return std::numeric_limits<double>::infinity();
      case 245: return -std::numeric_limits<double>::infinity();
      case 246: return std::numeric_limits<double>::denorm_min();
      case 247: return std::nextafter(lo, -std::numeric_limits<double>::infinity());
      case 248: return std::nextafter(hi, std::numeric_limits<double>::infinity());
      default: return bytes_.ConsumeFloatingPoint<double>();
    }
  }

  std::size_t count(std::size_t lo, std::size_t hi) { return bytes_.ConsumeIntegralInRange(lo, hi); }
  bool flag() { return bytes_.ConsumeBool(); }

  mm::footprint shape() {
    switch (count(0, 2)) {
      case 0: return mm::rectangle{number(0.1, 20.0), number(0.1, 5.0)};
      case 1: return mm::disc{number(0.05, 3.0)};
      default: {
        // A convex polygon: points on a circle at increasing angles, radii varied.
        mm::convex_polygon polygon;
        const std::size_t n = count(1, 10);
        double angle = number(-3.2, 3.2);
        for (std::size_t k = 0; k < n; ++k) {
          const double r = number(0.05, 4.0);
          polygon.vertices.push_back({r * std::cos(angle), r * std::sin(angle)});
          angle += number(0.0, 2.5);
        }
        return polygon;
      }
    }
  }

  mm::plan_input input() {
    mm::plan_input in;
    in.time = number(0.0, 100.0);
    in.ego.pose = {{number(-100.0, 100.0), number(-100.0, 100.0)}, number(-7.0, 7.0)};
    in.ego.speed = number(0.0, 35.0);
    if (flag()) in.ego.shape = shape();
    if (flag()) {
      in.ego.limits = {number(0.0, 8.0),  number(0.0, 12.0), number(0.0, 10.0),
                       number(0.5, 30.0), number(0.0, 60.0), flag()};
    }
    in.nominal = {number(-12.0, 8.0), number(-0.5, 0.5)};

    mm::planner_config& c = in.config;
    c.resolution = {count(1, 9), count(0, 11)};
    c.forecast_count = count(0, 17);
    if (flag()) {
      c.displacement_horizon = number(0.1, 3.0);
      c.collision_window = number(c.displacement_horizon, 6.0);
      c.forecast_step = number(0.05, 0.5);
      c.history_window = number(0.02, 2.0);
      c.max_time_step = number(0.005, 0.2);
    }
    c.safety_margin = number(0.0, 1.5);
    switch (count(0, 2)) {
      case 0: c.policy.kind = mm::forecast_policy_kind::adjustable; break;
      case 1: c.policy.kind = mm::forecast_policy_kind::constant; break;
      default: c.policy.kind = mm::forecast_policy_kind::robust; break;
    }
    c.policy.constant_forecast_time = c.forecast_step * static_cast<double>(count(0, 20));
    if (flag()) c.effort = {number(0.0, 10.0), number(0.0, 10.0)};
    c.urgent_steering = flag();
    if (flag()) {
      c.assignment_search = mm::assignment_search_kind::exhaustive;
      c.max_exhaustive_assignments = count(1, 400);
    }
    c.record_samples = flag();
    c.map_column = flag();
    c.decision_only = flag();

    const std::size_t obstacles = count(0, 4);
    for (std::size_t j = 0; j < obstacles; ++j) in.obstacles.push_back(track(static_cast<std::uint32_t>(j + 1), in));

    if (flag()) {
      // A road: a few quadrilaterals around the ego's start, some open at their ends.
      std::vector<std::vector<mm::vec2>> polygons;
      const std::size_t n = count(1, 3);
      for (std::size_t k = 0; k < n; ++k) {
        const mm::vec2 from{in.ego.pose.position.x + number(-30.0, 5.0), in.ego.pose.position.y + number(-10.0, 10.0)};
        const mm::vec2 to{from.x + number(-10.0, 60.0), from.y + number(-30.0, 30.0)};
        const double half = number(0.5, 6.0);
        const double dx = to.x - from.x;
        const double dy = to.y - from.y;
        const double length = std::max(std::hypot(dx, dy), 1e-9);
        const mm::vec2 side{-dy / length * half, dx / length * half};
        polygons.push_back({{from.x - side.x, from.y - side.y},
                            {to.x - side.x, to.y - side.y},
                            {to.x + side.x, to.y + side.y},
                            {from.x + side.x, from.y + side.y}});
      }
      std::vector<mm::polygon_edge> open;
      if (flag()) open.push_back({0, 1});
      if (flag()) open.push_back({n - 1, 3});
      try {
        in.drivable_area = std::make_shared<const mm::drivable_area>(std::move(polygons), open);
      } catch (const std::invalid_argument&) {
        // Not an area (its message is the drivable area's own concern): plan without it.
      }
    }
    return in;
  }

  /// The next planning step of `in`'s scene: later, the ego moved, its speed and nominal maneuver
  /// changed (or not), sometimes its footprint or the sampling resolution, every obstacle observed
  /// once more.
  void next_step(mm::plan_input& in) {
    const double dt = number(0.0, 0.1);
    in.time += dt;
    in.ego.pose.position.x += number(-1.0, 1.0);
    in.ego.pose.position.y += number(-1.0, 1.0);
    if (flag()) in.ego.speed = flag() ? in.ego.speed + number(-0.5, 0.5) : number(0.0, 35.0);
    if (flag()) in.nominal = {number(-12.0, 8.0), number(-0.5, 0.5)};
    if (flag()) in.ego.shape = shape();
    if (flag()) in.config.resolution = {count(1, 9), count(0, 11)};
    for (mm::obstacle_track& t : in.obstacles) {
      mm::observation last = t.history.back();
      last.time = in.time;
      last.pose.position.x += number(-1.0, 1.0);
      last.pose.position.y += number(-1.0, 1.0);
      t.history.push_back(last);
      if (t.motion) t.motion->pose = last.pose;
    }
  }

 private:
  /// A road user moving at a steady speed and turn rate, observed with noise up to the planning
  /// time; or with its motion given.
  mm::obstacle_track track(std::uint32_t id, const mm::plan_input& in) {
    mm::obstacle_track t;
    t.id = id;
    t.kind = static_cast<mm::obstacle_kind>(count(0, 2));
    t.shape = shape();
    const mm::vec2 start{in.ego.pose.position.x + number(-60.0, 60.0), in.ego.pose.position.y + number(-60.0, 60.0)};
    double heading = number(-3.2, 3.2);
    const double speed = number(0.0, 30.0);
    const double yaw_rate = number(-1.5, 1.5);
    const double noise = flag() ? number(0.0, 0.5) : 0.0;
    const std::size_t n = count(1, 40);
    const double step = number(0.01, 0.2);
    mm::vec2 at = start;
    for (std::size_t k = 0; k < n; ++k) {
      const double time = in.time - step * static_cast<double>(n - 1 - k);
      t.history.push_back({time,
                           {{at.x + noise * number(-1.0, 1.0), at.y + noise * number(-1.0, 1.0)},
                            heading + noise * number(-0.2, 0.2)},
                           speed + noise * number(-1.0, 1.0)});
      at.x += speed * step * std::cos(heading);
      at.y += speed * step * std::sin(heading);
      heading += yaw_rate * step;
    }
    if (flag()) t.motion = mm::motion_estimate{t.history.back().pose, number(0.0, 30.0), number(-1.5, 1.5)};
    return t;
  }

  FuzzedDataProvider bytes_;
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Stops the fuzzer with what failed and the step's command, mode and indices.
void require(bool ok, const char* what, const mm::plan_input& in, const mm::plan_result& r) {
  if (ok) return;
  std::fprintf(stderr,
               "planner_fuzzer: %s\n  ego speed %.17g, limits a_max %.17g d_max %.17g a_lat %.17g R_min %.17g "
               "v_cap %.17g steering %d\n  command (%.17g, %.17g), mode %d, family %d, tau index %zu, "
               "MI- %.17g, MI+ %.17g, TTC %.17g\n",
               what, in.ego.speed, in.ego.limits.max_acceleration, in.ego.limits.max_deceleration,
               in.ego.limits.max_lateral_acceleration, in.ego.limits.min_turning_radius, in.ego.limits.speed_cap,
               in.ego.limits.steering ? 1 : 0, r.command.acceleration, r.command.curvature, static_cast<int>(r.mode),
               static_cast<int>(r.selected_family), r.forecast_index, r.mi_brake_selected, r.mi_accelerate_selected,
               r.time_to_collision);
  std::abort();
}

bool in_unit_interval(double x) { return x >= 0.0 && x <= 1.0; }

}  // namespace

/// Plans `in` from scratch and with `kept` (which planned the inputs before it), and checks both.
void check(const mm::plan_input& in, mm::planner& kept) {
  const mm::plan_result r = mm::plan(in);
  const mm::plan_result again = kept.plan(in);
  require(again.status == r.status && again.error == r.error, "a kept planner's status differs", in, r);
  if (!r.ok()) {
    require(!r.error.empty(), "refused without a message", in, r);
    return;
  }
  require(same_bits(again.command.acceleration, r.command.acceleration) &&
              same_bits(again.command.curvature, r.command.curvature) && again.mode == r.mode &&
              again.forecast_index == r.forecast_index && same_bits(again.mi_brake_selected, r.mi_brake_selected) &&
              same_bits(again.mi_accelerate_selected, r.mi_accelerate_selected) &&
              std::equal(again.mi_brake.begin(), again.mi_brake.end(), r.mi_brake.begin(), r.mi_brake.end(), same_bits) &&
              std::equal(again.mi_accelerate.begin(), again.mi_accelerate.end(), r.mi_accelerate.begin(),
                         r.mi_accelerate.end(), same_bits),
          "a kept planner's result differs", in, r);
  if (!r.indices_computed) {
    // decision_only's shortcut: u_nom, the command of the full step (method.md §4.6).
    require(in.config.decision_only && r.mode == mm::planning_mode::nominal, "a step without indices is not nominal",
            in, r);
    mm::plan_input full_input = in;
    full_input.config.decision_only = false;
    const mm::plan_result full = mm::plan(full_input);
    require(full.ok() && full.mode == r.mode && same_bits(full.command.acceleration, r.command.acceleration) &&
                same_bits(full.command.curvature, r.command.curvature) &&
                same_bits(full.time_to_collision, r.time_to_collision),
            "deciding only the command differs from the full step", in, r);
  }
  // The command: finite and within the limits (spec §8.4).
  const mm::ego_limits& limits = in.ego.limits;
  require(std::isfinite(r.command.acceleration) && std::isfinite(r.command.curvature), "the command is not finite",
          in, r);
  require(r.command.acceleration >= -limits.max_deceleration && r.command.acceleration <= limits.max_acceleration,
          "the command's acceleration is outside the limits", in, r);
  require(std::abs(r.command.curvature) <= mm::max_curvature(in.ego.speed, limits),
          "the command's curvature is outside the limits", in, r);
  // The indices and the map column (spec §6).
  require(in_unit_interval(r.mi_brake_selected) && in_unit_interval(r.mi_accelerate_selected),
          "a selected index is outside [0, 1]", in, r);
  const std::size_t column = in.config.map_column || in.config.record_samples ? in.config.forecast_count : 0;
  require(r.mi_brake.size() == column && r.mi_accelerate.size() == column, "the map column has the wrong size", in, r);
  require(std::all_of(r.mi_brake.begin(), r.mi_brake.end(), in_unit_interval) &&
              std::all_of(r.mi_accelerate.begin(), r.mi_accelerate.end(), in_unit_interval),
          "an index of the map column is outside [0, 1]", in, r);
  require(r.excluded.size() == in.config.forecast_count && r.forecast_index < in.config.forecast_count,
          "the excluded forecast times or the selected one do not fit the grid", in, r);
  require(r.forecast_time >= 0.0 && std::isfinite(r.forecast_time), "the selected forecast time is not finite", in, r);
  require(r.time_to_collision >= 0.0, "the time to collision is negative or NaN", in, r);
  require(r.obstacles.size() == in.obstacles.size(), "an obstacle's assessment is missing", in, r);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  decoder decode(data, size);
  mm::planner kept;
  mm::plan_input in = decode.input();
  check(in, kept);
  // Up to three more steps with the same planner: the next step of the same scene (the ego's speed,
  // pose and nominal maneuver changed), or another scene.
  const std::size_t steps = decode.count(0, 3);
  for (std::size_t k = 0; k < steps; ++k) {
    if (decode.flag()) {
      decode.next_step(in);
    } else {
      in = decode.input();
    }
    check(in, kept);
  }
  return 0;
}
