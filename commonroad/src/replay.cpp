#include "mm/commonroad/replay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "mm/commonroad/measure.hpp"
#include "mm/footprint.hpp"
#include "mm/geometry.hpp"
#include "mm/number_text.hpp"
#include "recording.hpp"

namespace mm::commonroad {

using namespace detail;

namespace {

/// Positions closer than this to the previous kept one are the same path point [m].
constexpr double same_point = 1e-3;


/// The path along a road user's recorded positions and how far along it each state is [m].
struct recorded_path {
  std::vector<vec2> points;
  std::vector<double> arc_length;  ///< per state
};

recorded_path path_of(const obstacle& o) {
  recorded_path p;
  double travelled = 0.0;
  for (const state& x : o.states) {
    if (p.points.empty()) {
      p.points.push_back(x.position);
    } else if (const double d = norm(x.position - p.points.back()); d >= same_point) {
      travelled += d;
      p.points.push_back(x.position);
    }
    p.arc_length.push_back(travelled);
  }
  return p;
}

/// Speed held over each recorded step so that the road user is at its recorded arc length at every
/// recorded step: the knots (τ_i, v_i) and (τ_{i+1} − ε, v_i) with v_i = (s_{i+1} − s_i)/Δt, then a
/// speed of at least 1 m/s after its last state, so that it leaves the scene at once.
sim::speed_profile profile_of(const recorded_path& p, double dt) {
  sim::speed_profile profile;
  const double epsilon = dt * 1e-6;
  const std::size_t n = p.arc_length.size();
  double last = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double tau = dt * static_cast<double>(i);
    last = (p.arc_length[i + 1] - p.arc_length[i]) / dt;
    profile.knots.push_back({tau, last});
    profile.knots.push_back({tau + dt - epsilon, last});
  }
  profile.knots.push_back({dt * static_cast<double>(n - 1), std::max(last, 1.0)});
  return profile;
}

measure_error cannot_replay(const obstacle& o, const std::string& why) {
  return measure_error("road user " + std::to_string(o.id) + " (" + o.type + "): " + why);
}

/// `cannot_replay` unless the footprint of `o` is at least `sim::smallest_road_user_size` across
/// and it moves no faster than `sim::largest_road_user_speed`, as in a scenario file: every speed of
/// `profile`, or when there is none, of its recorded states.
void check_limits(const obstacle& o, const sim::speed_profile* profile, double dt) {
  if (smallest_dimension(o.shape) < sim::smallest_road_user_size) {
    throw cannot_replay(o, "its footprint is " + number_text(smallest_dimension(o.shape)) +
                               " m across: expected at least 0.05 m, as in a scenario file");
  }
  const auto too_fast = [&](double v, double t) {
    if (!(v <= sim::largest_road_user_speed)) {
      throw cannot_replay(o, "it moves at " + number_text(v) + " m/s, " + number_text(t) +
                                 " s after its start: expected at most 100 m/s, as in a scenario file");
    }
  };
  if (profile != nullptr) {
    for (const sim::speed_knot& k : profile->knots) too_fast(k.speed, k.time);
    return;
  }
  for (const state& x : o.states) too_fast(x.velocity, static_cast<double>(x.step - o.states.front().step) * dt);
}

/// The polyline through `points`, or `cannot_replay` when it is not one (lengths that overflow).
sim::path polyline_of(const obstacle& o, const std::vector<vec2>& points) {
  try {
    return sim::path::polyline(points);
  } catch (const std::invalid_argument& e) {
    throw cannot_replay(o, std::string("its recorded positions make no path: ") + e.what());
  }
}

}  // namespace

sim::scripted_car_following reactive_traffic() {
  sim::scripted_car_following k;
  k.follows_scripted = false;
  return k;
}

std::string replay_name(const obstacle& o) {
  return (o.type.empty() ? "obstacle" : o.type) + "-" + std::to_string(o.id);
}

sim::scenario replay_scenario(const scenario& s, const replay_options& options) {
  const obstacle& agent = measured(s, options.agent);
  sim::scenario out;
  out.name = s.benchmark_id.empty() ? "commonroad" : s.benchmark_id;
  out.description = "CommonRoad " + s.version + " recording " + s.benchmark_id + ", road user " +
                    std::to_string(agent.id) + " driven by the planner";
  out.time_step = 0.01;
  std::int64_t last_step = 0;
  for (const obstacle& o : s.obstacles) {
    if (!o.states.empty()) last_step = std::max(last_step, o.states.back().step);
  }
  out.duration = std::max(step_time(s, last_step), out.time_step);
  if (!(out.duration / out.time_step <= sim::largest_step_count)) {
    throw measure_error("the recording lasts " + number_text(out.duration, 6) + " s (timeStepSize " +
                        number_text(s.time_step, 6) + " s): expected at most 10^7 simulation steps of 0.01 s (" +
                        number_text(sim::largest_step_count * out.time_step, 6) + " s) to replay");
  }

  const auto* body = std::get_if<rectangle>(&agent.shape);
  if (body == nullptr) throw cannot_replay(agent, "the planner drives a rectangular footprint; this one is not");
  check_limits(agent, nullptr, s.time_step);
  const recorded_path route = path_of(agent);
  if (route.points.size() < 2) throw cannot_replay(agent, "it does not move, so it has no path to follow");
  sim::planning_vehicle ego;
  ego.name = replay_name(agent);
  ego.path = polyline_of(agent, route.points);
  ego.start_time = step_time(s, agent.states.front().step);
  ego.initial_speed = std::max(agent.states.front().velocity, 0.0);
  sim::speed_profile recorded;
  for (std::size_t i = 0; i < agent.states.size(); ++i) {
    recorded.knots.push_back({s.time_step * static_cast<double>(i), std::max(agent.states[i].velocity, 0.0)});
  }
  if (options.desired_speed) {
    ego.desired_speed = *options.desired_speed;
  } else {
    ego.desired_speed = ego.initial_speed;
    ego.desired_speed_profile = std::move(recorded);
  }
  ego.shape = *body;
  ego.limits = options.limits;
  ego.limits.speed_cap = std::max({ego.limits.speed_cap, largest_speed(agent), ego.desired_speed});
  ego.planner = options.config;
  ego.avoidance = options.avoidance;
  out.planning_vehicles.push_back(std::move(ego));

  for (const obstacle& o : s.obstacles) {
    if (o.id == agent.id || o.states.empty()) continue;
    recorded_path p = path_of(o);
    if (o.role == obstacle_role::static_obstacle) {
      check_limits(o, nullptr, s.time_step);
      out.static_obstacles.push_back({replay_name(o), world_polygon(o.shape, o.states.front())});
      continue;
    }
    const bool moves = p.points.size() >= 2;
    if (!moves) {
      // Standing for its recorded steps: a path of 1 mm along its heading, which it leaves at once
      // after its last state as a moving road user does.
      const state& x = o.states.front();
      p.points.push_back({x.position.x + same_point * std::cos(x.orientation),
                          x.position.y + same_point * std::sin(x.orientation)});
    }
    sim::scripted_motion motion;
    motion.path = polyline_of(o, p.points);
    motion.start_time = step_time(s, o.states.front().step);
    motion.speed = profile_of(p, s.time_step);
    check_limits(o, &motion.speed, s.time_step);
    if (const auto* r = std::get_if<rectangle>(&o.shape)) {
      out.scripted_vehicles.push_back({replay_name(o), std::move(motion), *r, moves ? options.reactive : std::nullopt});
    } else if (const auto* d = std::get_if<disc>(&o.shape)) {
      out.pedestrians.push_back({replay_name(o), std::move(motion), d->radius});
    } else {
      throw cannot_replay(o, "a moving polygon (an offset shape in the file): the simulator moves rectangles "
                             "and discs");
    }
  }
  if (options.on_lanelets) {
    try {
      out.drivable_area = lanelet_polygons(s);
    } catch (const std::invalid_argument& e) {
      throw measure_error(std::string("the replay on the lanelets: ") + e.what());
    }
  }
  if (const auto problem = sim::validation_error(out)) {
    throw measure_error("the replay of road user " + std::to_string(agent.id) +
                        " is not a valid simulation: " + *problem);
  }
  return out;
}

}  // namespace mm::commonroad
