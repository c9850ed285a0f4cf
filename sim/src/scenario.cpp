#include "mm/sim/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string_view>
#include <utility>

#include "mm/drivable_area.hpp"
#include "mm/footprint.hpp"
#include "mm/number_text.hpp"
#include "mm/planner.hpp"

namespace mm::sim {
namespace {

/// Collects the first problem; `where` names the agent (or "scenario") being checked.
class checker {
 public:
  std::optional<std::string> error;
  std::string where;
  double duration = 0.0;  ///< of the run [s]

  void fail(const std::string& field, const std::string& message) {
    if (!error) error = where + (where.empty() ? "" : ": ") + field + message;
  }
  void require(bool ok, const std::string& field, double value, const std::string& expected) {
    if (!ok) fail(field, " = " + number_text(value) + ": expected " + expected);
  }
  void positive(const std::string& field, double value, const std::string& unit) {
    require(std::isfinite(value) && value > 0.0, field, value, "a positive finite number [" + unit + "]");
  }
  void non_negative(const std::string& field, double value, const std::string& unit) {
    require(std::isfinite(value) && value >= 0.0, field, value, "a finite number ≥ 0 [" + unit + "]");
  }
  void finite(const std::string& field, double value, const std::string& unit) {
    require(std::isfinite(value), field, value, "a finite number [" + unit + "]");
  }

  void path_start(const std::string& prefix, const path& p, double start_arc_length) {
    if (p.empty()) {
      fail(prefix + "path", ": the path is empty");
      return;
    }
    // Every point of a segment lies within its length of its start.
    for (const path_segment& s : p.segments()) {
      const double reach = std::max(std::abs(s.start.position.x), std::abs(s.start.position.y)) + s.length;
      if (!(reach <= largest_path_coordinate)) {
        fail(prefix + "path", ": a segment from (" + number_text(s.start.position.x) + ", " +
                                  number_text(s.start.position.y) + ") m of length " + number_text(s.length) +
                                  " m reaches beyond ±" + number_text(largest_path_coordinate) +
                                  " m: road users must stay within the ±" +
                                  number_text(mm::largest_input_coordinate) + " m the planner takes");
        return;
      }
    }
    require(std::isfinite(start_arc_length) && start_arc_length >= 0.0 && start_arc_length < p.length(),
            prefix + "start_arc_length", start_arc_length,
            "an arc length in [0, " + number_text(p.length()) + ") m, the path's length");
  }

  /// A road user that can move at up to `speed` [m/s] travels at most `largest_travel` in the run.
  void travel(const std::string& field, double speed) {
    require(!(speed * duration > largest_travel), field, speed,
            "a speed at which the run's " + number_text(duration) + " s cover at most " + number_text(largest_travel) +
                " m, so that road users stay within the ±" + number_text(mm::largest_input_coordinate) +
                " m the planner takes");
  }

  void profile(const std::string& field, const speed_profile& profile) {
    const auto& knots = profile.knots;
    if (knots.empty()) fail(field, ": the speed profile has no knots");
    for (std::size_t i = 0; i < knots.size(); ++i) {
      const std::string at = field + ".knots[" + std::to_string(i) + "]";
      non_negative(at + ".time", knots[i].time, "s");
      non_negative(at + ".speed", knots[i].speed, "m/s");
      require(!(knots[i].speed > largest_road_user_speed), at + ".speed", knots[i].speed,
              "at most " + number_text(largest_road_user_speed) + " m/s");
      travel(at + ".speed", knots[i].speed);
      if (i > 0) {
        require(knots[i].time > knots[i - 1].time, at + ".time", knots[i].time,
                "a time after the previous knot's " + number_text(knots[i - 1].time) + " s");
      }
    }
  }

  void motion(const std::string& prefix, const scripted_motion& m) {
    path_start(prefix, m.path, m.start_arc_length);
    non_negative(prefix + "start_time", m.start_time, "s");
    profile(prefix + "speed", m.speed);
    if (m.stop) {
      require(std::isfinite(m.stop->arc_length) && m.stop->arc_length >= m.start_arc_length &&
                  m.stop->arc_length <= m.path.length(),
              prefix + "stop.arc_length", m.stop->arc_length,
              "an arc length from start_arc_length = " + number_text(m.start_arc_length) + " m to the path's length " +
                  number_text(m.path.length()) + " m");
      if (m.stop->duration) positive(prefix + "stop.duration", *m.stop->duration, "s");
    }
  }

  void car_following(const std::string& prefix, const car_following_config& k) {
    non_negative(prefix + "time_gap", k.time_gap, "s");
    non_negative(prefix + "jam_distance", k.jam_distance, "m");
    positive(prefix + "corridor_half_width", k.corridor_half_width, "m");
    require(k.max_heading_difference >= 0.0 && k.max_heading_difference <= std::numbers::pi,
            prefix + "max_heading_difference", k.max_heading_difference, "an angle from 0 to π [rad]");
  }

  void scripted_following(const std::string& prefix, const scripted_car_following& k) {
    car_following(prefix, k.following);
    positive(prefix + "max_acceleration", k.max_acceleration, "m/s²");
    positive(prefix + "comfortable_deceleration", k.comfortable_deceleration, "m/s²");
    positive(prefix + "max_deceleration", k.max_deceleration, "m/s²");
    positive(prefix + "speed_gain", k.speed_gain, "1/s");
  }

  void rectangle(const std::string& prefix, const mm::rectangle& r) {
    positive(prefix + "shape.length", r.length, "m");
    positive(prefix + "shape.width", r.width, "m");
    if (auto why = mm::footprint_error(r)) fail(prefix + "shape", ": " + *why);
  }
};

std::string agent_label(std::string_view list, std::size_t index, const std::string& name) {
  return std::string(list) + "[" + std::to_string(index) + "] \"" + name + "\"";
}

void check_planning_vehicle(checker& c, const planning_vehicle& v, double time_step) {
  c.path_start("", v.path, v.start_arc_length);
  c.require(std::abs(v.start_lateral_offset) <= largest_lateral_offset, "start_lateral_offset", v.start_lateral_offset,
            "a finite offset within ±" + number_text(largest_lateral_offset) + " [m]");
  c.non_negative("start_time", v.start_time, "s");
  c.non_negative("initial_speed", v.initial_speed, "m/s");
  c.non_negative("desired_speed", v.desired_speed, "m/s");
  c.travel("limits.speed_cap", v.limits.speed_cap);
  if (v.desired_speed_profile) c.profile("desired_speed_profile", *v.desired_speed_profile);
  c.rectangle("", v.shape);
  c.positive("follower.lookahead_time", v.follower.lookahead_time, "s");
  c.positive("follower.min_lookahead", v.follower.min_lookahead, "m");
  c.positive("follower.speed_gain", v.follower.speed_gain, "1/s");
  c.positive("follower.comfortable_deceleration", v.follower.comfortable_deceleration, "m/s²");
  if (v.follower.curve_lateral_acceleration) {
    c.positive("follower.curve_lateral_acceleration", *v.follower.curve_lateral_acceleration, "m/s²");
  }
  if (v.follower.car_following) c.car_following("follower.car_following.", *v.follower.car_following);
  c.require(v.planning_period >= 1, "planning_period", static_cast<double>(v.planning_period),
            "an integer ≥ 1 [steps]");
  c.require(v.planner.history_window >= time_step, "planner.history_window", v.planner.history_window,
            "at least the time step " + number_text(time_step) + " s, so that a track holds two observations");
  c.require(!(v.planner.history_window / time_step > largest_history_steps), "planner.history_window",
            v.planner.history_window,
            "at most " + number_text(largest_history_steps) + " time steps of " + number_text(time_step) + " s (" +
                number_text(largest_history_steps * time_step) + " s), the longest track the simulator keeps");
  if (c.error || v.path.empty()) return;
  // The planner's own checks of the limits, the footprint and the configuration.
  mm::plan_input probe;
  probe.ego.pose = {v.path.at(v.start_arc_length).position, v.path.at(v.start_arc_length).heading};
  probe.ego.speed = v.initial_speed;
  probe.ego.shape = v.shape;
  probe.ego.limits = v.limits;
  probe.config = v.planner;
  if (auto why = mm::validation_error(probe)) {
    std::string field = *why;
    if (field.rfind("ego.limits.", 0) == 0) field = "limits." + field.substr(11);
    else if (field.rfind("ego.speed", 0) == 0) field = "initial_speed" + field.substr(9);
    // The configuration's fields, wherever the message names them: planner.*.
    for (std::size_t at = field.find("config."); at != std::string::npos; at = field.find("config.", at)) {
      field.replace(at, 7, "planner.");
    }
    c.fail("", field);
  }
}

}  // namespace

vec2 static_reference_point(const static_obstacle& obstacle) {
  vec2 sum;
  for (const vec2& v : obstacle.vertices) sum = sum + v;
  return obstacle.vertices.empty() ? sum : (1.0 / static_cast<double>(obstacle.vertices.size())) * sum;
}

mm::convex_polygon static_footprint(const static_obstacle& obstacle) {
  const vec2 reference = static_reference_point(obstacle);
  mm::convex_polygon polygon;
  for (const vec2& v : obstacle.vertices) polygon.vertices.push_back(v - reference);
  return polygon;
}

std::optional<std::string> validation_error(const scenario& s) {
  checker c;
  c.where = "scenario";
  c.duration = s.duration;
  c.positive("duration", s.duration, "s");
  c.positive("time_step", s.time_step, "s");
  c.require(!(s.time_step > s.duration), "time_step", s.time_step,
            "at most the duration " + number_text(s.duration) + " s");
  c.require(!(s.duration / s.time_step > largest_step_count), "duration", s.duration,
            "at most 10^7 time steps of " + number_text(s.time_step) + " s (" + number_text(largest_step_count * s.time_step) +
                " s)");
  c.non_negative("noise.position_sd", s.noise.position_sd, "m");
  c.require(!(s.noise.position_sd > largest_noise_sd), "noise.position_sd", s.noise.position_sd,
            "at most " + number_text(largest_noise_sd) + " m");
  c.non_negative("noise.heading_sd", s.noise.heading_sd, "rad");
  c.non_negative("noise.speed_sd", s.noise.speed_sd, "m/s");
  c.require(!(s.noise.speed_sd > largest_noise_sd), "noise.speed_sd", s.noise.speed_sd,
            "at most " + number_text(largest_noise_sd) + " m/s");

  std::set<std::string> names;
  const auto name = [&](std::string_view list, std::size_t i, const std::string& n) {
    c.where = agent_label(list, i, n);
    if (n.empty()) c.fail("name", ": expected a non-empty name");
    if (!names.insert(n).second) c.fail("name", ": another agent already has this name");
  };
  for (std::size_t i = 0; i < s.planning_vehicles.size() && !c.error; ++i) {
    name("planning_vehicles", i, s.planning_vehicles[i].name);
    check_planning_vehicle(c, s.planning_vehicles[i], s.time_step);
  }
  for (std::size_t i = 0; i < s.scripted_vehicles.size() && !c.error; ++i) {
    name("scripted_vehicles", i, s.scripted_vehicles[i].name);
    c.motion("motion.", s.scripted_vehicles[i].motion);
    c.rectangle("", s.scripted_vehicles[i].shape);
    if (s.scripted_vehicles[i].car_following) c.scripted_following("car_following.", *s.scripted_vehicles[i].car_following);
  }
  for (std::size_t i = 0; i < s.pedestrians.size() && !c.error; ++i) {
    name("pedestrians", i, s.pedestrians[i].name);
    c.motion("motion.", s.pedestrians[i].motion);
    c.positive("radius", s.pedestrians[i].radius, "m");
    if (auto why = mm::footprint_error(mm::disc{s.pedestrians[i].radius})) c.fail("radius", ": " + *why);
  }
  for (std::size_t i = 0; i < s.static_obstacles.size() && !c.error; ++i) {
    const static_obstacle& o = s.static_obstacles[i];
    name("static_obstacles", i, o.name);
    for (std::size_t k = 0; k < o.vertices.size() && !c.error; ++k) {
      const std::string at = "vertices[" + std::to_string(k) + "]";
      for (const auto& [axis, value] : {std::pair{".x", o.vertices[k].x}, std::pair{".y", o.vertices[k].y}}) {
        c.require(std::abs(value) <= mm::largest_input_coordinate, at + axis, value,
                  "a finite coordinate within ±" + number_text(mm::largest_input_coordinate) + " [m]");
      }
    }
    if (c.error) break;
    if (auto why = mm::footprint_error(static_footprint(o))) c.fail("vertices", ": " + *why);
  }
  if (!c.error && !s.drivable_area.empty()) {
    c.where = "scenario";
    if (auto why = mm::drivable_area_error(s.drivable_area.polygons, s.drivable_area.open_edges)) {
      c.fail("drivable_area", ": " + *why);
    }
  }
  return c.error;
}

std::optional<std::string> command_error(const planning_vehicle& v, double speed, const mm::maneuver& u) {
  const ego_limits& limits = v.limits;
  if (!std::isfinite(u.acceleration) || u.acceleration < -limits.max_deceleration ||
      u.acceleration > limits.max_acceleration) {
    return "acceleration = " + number_text(u.acceleration) + ": expected from " + number_text(-limits.max_deceleration) +
           " to " + number_text(limits.max_acceleration) + " [m/s²]";
  }
  const double most = mm::max_curvature(speed, limits);
  if (!std::isfinite(u.curvature) || std::abs(u.curvature) > most) {
    return "curvature = " + number_text(u.curvature) + ": expected from " + number_text(-most) + " to " + number_text(most) +
           " [1/m] at its speed of " + number_text(speed) + " m/s";
  }
  return std::nullopt;
}

}  // namespace mm::sim
