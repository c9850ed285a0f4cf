#include "random_scenes.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

namespace mm::testing {

std::vector<observation> ctrv_history(const pose& current, double speed, double yaw_rate, double now,
                                      std::size_t count, double step) {
  // Run the motion backwards: reversing time on a CTRV arc is the same arc driven with heading
  // + π and the opposite turn rate.
  const motion_estimate backwards{{current.position, current.heading + std::numbers::pi}, speed, -yaw_rate};
  std::vector<observation> history(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double age = static_cast<double>(count - 1 - k) * step;
    const pose p = forecast_pose(backwards, age, age);
    history[k] = {now - age, {p.position, wrap_angle(p.heading - std::numbers::pi)}, speed};
  }
  return history;
}

plan_input random_scene(std::mt19937_64& rng, const scene_options& options) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  std::normal_distribution<double> gauss(0.0, 1.0);

  plan_input in;
  in.time = uniform(0.0, 10.0);
  in.ego.pose = {{uniform(-50.0, 50.0), uniform(-50.0, 50.0)}, uniform(-std::numbers::pi, std::numbers::pi)};
  in.ego.speed = unit(rng) < 0.05 ? 0.0 : uniform(1.0, 20.0);
  in.nominal = {uniform(-1.0, 1.0), uniform(-0.02, 0.02)};

  for (std::size_t j = 0; j < options.obstacles; ++j) {
    obstacle_track track;
    track.id = static_cast<std::uint32_t>(j + 1);
    const double kind_draw = unit(rng);
    double speed = 0.0;
    if (options.allow_static && kind_draw < 0.1) {
      track.kind = obstacle_kind::static_obstacle;
      track.shape = convex_polygon{{{2.0, 0.0}, {0.5, 1.5}, {-1.5, 1.0}, {-1.5, -1.0}, {0.5, -1.5}}};
    } else if (kind_draw < 0.35) {
      track.kind = obstacle_kind::pedestrian;
      track.shape = disc{0.35};
      speed = uniform(0.0, 2.5);
    } else {
      track.kind = obstacle_kind::vehicle;
      track.shape = rectangle{uniform(3.5, 5.5), uniform(1.6, 2.1)};
      speed = uniform(0.0, 15.0);
    }
    const double yaw_rate = track.kind == obstacle_kind::vehicle ? uniform(-0.5, 0.5) : uniform(-0.2, 0.2);

    // Aim: the obstacle reaches a point of the ego's straight path at the time the ego would.
    pose current;
    if (unit(rng) < options.conflict_probability) {
      const double meet_time = uniform(0.3, 2.8);
      const double ego_travel = in.ego.speed * meet_time;
      const vec2 meet = to_world(in.ego.pose, {ego_travel + uniform(-3.0, 3.0), uniform(-2.0, 2.0)});
      const double approach = uniform(-std::numbers::pi, std::numbers::pi);
      // Start so that straight motion along `approach` reaches `meet` at meet_time.
      current = {meet - speed * meet_time * unit_vector(approach), approach};
      if (speed < 0.5) current.position = meet + uniform(2.0, 5.0) * unit_vector(approach);
    } else {
      current = {to_world(in.ego.pose, {uniform(-60.0, 60.0), uniform(-60.0, 60.0)}),
                 uniform(-std::numbers::pi, std::numbers::pi)};
    }
    if (track.kind == obstacle_kind::static_obstacle) {
      track.history = {{in.time, current, 0.0}};
    } else {
      track.history = ctrv_history(current, speed, yaw_rate, in.time);
      if (options.sensor_noise) {
        for (observation& o : track.history) {
          o.pose.position = o.pose.position + vec2{0.05 * gauss(rng), 0.05 * gauss(rng)};
          o.pose.heading += 0.5 * std::numbers::pi / 180.0 * gauss(rng);
          o.speed += 0.1 * gauss(rng);
        }
      }
    }
    in.obstacles.push_back(std::move(track));
  }
  return in;
}

namespace {

void put(std::ostringstream& out, const footprint& f) {
  if (const auto* r = std::get_if<rectangle>(&f)) {
    out << "rectangle{" << r->length << ", " << r->width << "}";
  } else if (const auto* d = std::get_if<disc>(&f)) {
    out << "disc{" << d->radius << "}";
  } else {
    out << "convex_polygon{{";
    for (const vec2& v : std::get<convex_polygon>(f).vertices) out << "{" << v.x << ", " << v.y << "}, ";
    out << "}}";
  }
}

}  // namespace

std::string describe(const plan_input& in) {
  std::ostringstream out;
  out << std::setprecision(17);
  out << "plan_input in;\nin.time = " << in.time << ";\n";
  out << "in.ego.pose = {{" << in.ego.pose.position.x << ", " << in.ego.pose.position.y << "}, "
      << in.ego.pose.heading << "};\nin.ego.speed = " << in.ego.speed << ";\nin.ego.shape = ";
  put(out, in.ego.shape);
  const ego_limits& l = in.ego.limits;
  out << ";\nin.ego.limits = {" << l.max_acceleration << ", " << l.max_deceleration << ", "
      << l.max_lateral_acceleration << ", " << l.min_turning_radius << ", " << l.speed_cap << ", "
      << (l.steering ? "true" : "false") << "};\n";
  out << "in.nominal = {" << in.nominal.acceleration << ", " << in.nominal.curvature << "};\n";
  const forecast_policy_kind kind = in.config.policy.kind;
  out << "in.config.policy = {forecast_policy_kind::"
      << (kind == forecast_policy_kind::constant ? "constant" : kind == forecast_policy_kind::robust ? "robust" : "adjustable")
      << ", " << in.config.policy.constant_forecast_time << "};\nin.config.safety_margin = " << in.config.safety_margin
      << ";\nin.config.urgent_steering = " << (in.config.urgent_steering ? "true" : "false") << ";\n";
  const auto flag = [&](const char* name, bool value) { out << "in.config." << name << " = " << (value ? "true" : "false") << ";\n"; };
  if (!in.config.map_column) flag("map_column", false);
  if (in.config.record_samples) flag("record_samples", true);
  if (in.config.decision_only) flag("decision_only", true);
  for (const obstacle_track& o : in.obstacles) {
    out << "in.obstacles.push_back({" << o.id << ", obstacle_kind::"
        << (o.kind == obstacle_kind::static_obstacle ? "static_obstacle" : to_string(o.kind)) << ", ";
    put(out, o.shape);
    out << ", {";
    for (const observation& h : o.history) {
      out << "{" << h.time << ", {{" << h.pose.position.x << ", " << h.pose.position.y << "}, " << h.pose.heading
          << "}, " << h.speed << "}, ";
    }
    out << "}});\n";
  }
  return out.str();
}

}  // namespace mm::testing
