#include "mm/commonroad/measure.hpp"

#include "recording.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mm::commonroad {

using namespace detail;

namespace {

obstacle_kind kind_of(const obstacle& o) {
  if (o.role == obstacle_role::static_obstacle) return obstacle_kind::static_obstacle;
  return is_pedestrian(o) ? obstacle_kind::pedestrian : obstacle_kind::vehicle;
}

}  // namespace

plan_input planning_input(const scenario& s, const measure_options& options, std::int64_t step,
                          std::vector<std::uint32_t>* ids) {
  const obstacle& agent = measured(s, options.agent);
  const state* now = state_at(agent, step);
  if (now == nullptr) {
    throw measure_error("road user " + std::to_string(options.agent) + " is not recorded at step " +
                        std::to_string(step) + ": its states run from step " +
                        std::to_string(agent.states.front().step) + " to " + std::to_string(agent.states.back().step));
  }
  plan_input in;
  in.time = step_time(s, step);
  in.config = options.config;
  in.ego.pose = pose{now->position, wrap_angle(now->orientation)};
  in.ego.speed = std::max(now->velocity, 0.0);
  in.ego.shape = agent.shape;
  in.ego.limits = options.limits;
  in.ego.limits.speed_cap = std::max(in.ego.limits.speed_cap, largest_speed(agent));
  in.nominal = recorded_maneuver(agent, static_cast<std::size_t>(now - agent.states.data()), s.time_step);
  in.drivable_area = options.drivable_area;
  if (ids != nullptr) ids->clear();

  const double window = options.config.history_window;
  for (const obstacle& o : s.obstacles) {
    if (o.id == agent.id || o.states.empty()) continue;
    obstacle_track track;
    track.id = o.id;
    track.kind = kind_of(o);
    track.shape = o.shape;
    if (track.kind == obstacle_kind::static_obstacle) {
      observation x = observed(s, o.states.front());
      x.time = in.time;  // a static obstacle stands where it was placed, whenever that was written
      x.speed = 0.0;
      track.history.push_back(x);
    } else {
      const state* last = state_at(o, step);
      if (last == nullptr) continue;
      if (last == &o.states.front()) {
        // Seen once: the recorded speed and yaw rate (0 when the file gives none), as no estimate can be made.
        const observation x = observed(s, *last);
        track.history.push_back(x);
        track.motion = motion_estimate{x.pose, x.speed, last->yaw_rate.value_or(0.0)};
      } else {
        const auto end = static_cast<std::ptrdiff_t>(last - o.states.data()) + 1;
        std::ptrdiff_t begin = end - 2;
        while (begin > 0 && in.time - step_time(s, o.states[static_cast<std::size_t>(begin - 1)].step) <= window + 1e-9) {
          --begin;
        }
        for (std::ptrdiff_t i = begin; i < end; ++i) track.history.push_back(observed(s, o.states[static_cast<std::size_t>(i)]));
      }
    }
    in.obstacles.push_back(std::move(track));
    if (ids != nullptr) ids->push_back(o.id);
  }
  return in;
}

measurement measure(const scenario& s, const measure_options& options) {
  const obstacle& agent = measured(s, options.agent);
  measurement m;
  m.agent = agent.id;
  planner p;
  for (const state& x : agent.states) {
    measured_step step;
    step.step = x.step;
    step.time = step_time(s, x.step);
    const plan_input in = planning_input(s, options, x.step, &step.obstacle_ids);
    step.ego = in.ego;
    step.recorded = in.nominal;
    step.result = p.plan(in);
    if (!step.result.ok()) {
      throw measure_error("road user " + std::to_string(agent.id) + " at step " + std::to_string(x.step) +
                          ": the planner refused its input: " + step.result.error);
    }
    m.steps.push_back(std::move(step));
  }
  return m;
}

maneuver recorded_maneuver(const obstacle& o, std::size_t k, double dt) {
  if (o.states.size() < 2) return {};
  const std::size_t from = k + 1 < o.states.size() ? k : k - 1;
  const state& a = o.states[from];
  const state& b = o.states[from + 1];
  maneuver u;
  u.acceleration = (std::max(b.velocity, 0.0) - std::max(a.velocity, 0.0)) / dt;
  const double distance = norm(b.position - a.position);
  if (distance >= 1e-3) u.curvature = wrap_angle(b.orientation - a.orientation) / distance;
  return u;
}

std::vector<std::uint32_t> measurable_road_users(const scenario& s) {
  std::vector<std::uint32_t> ids;
  for (const obstacle& o : s.obstacles) {
    if (can_be_measured(o)) ids.push_back(o.id);
  }
  return ids;
}

void require_measurable(const scenario& s, std::uint32_t agent) { static_cast<void>(measured(s, agent)); }

std::string measurable_road_users_text(const scenario& s) {
  constexpr std::size_t listed = 20;
  const std::vector<std::uint32_t> ids = measurable_road_users(s);
  if (ids.empty()) return "none";
  std::string text;
  for (std::size_t i = 0; i < ids.size() && i < listed; ++i) text += (i ? ", " : "") + std::to_string(ids[i]);
  if (ids.size() > listed) text += ", … (" + std::to_string(ids.size()) + " in all)";
  return text;
}

std::optional<std::uint32_t> recorded_ego(const scenario& s, const planning_problem& problem) {
  const auto measurable = [](const obstacle* o) { return o != nullptr && can_be_measured(*o); };
  if (const obstacle* o = find_obstacle(s, problem.id); measurable(o)) return o->id;
  if (problem.id > 90000) {
    if (const obstacle* o = find_obstacle(s, problem.id - 90000); measurable(o)) return o->id;
  }
  const state& start = problem.initial;
  for (const obstacle& o : s.obstacles) {
    if (!can_be_measured(o)) continue;
    const state* x = state_at(o, start.step);
    if (x == nullptr) x = &o.states.front();
    if (norm(x->position - start.position) <= 0.5 && std::abs(wrap_angle(x->orientation - start.orientation)) <= 0.1 &&
        std::abs(x->velocity - start.velocity) <= 0.5) {
      return o.id;
    }
  }
  return std::nullopt;
}

double room(const plan_result& result) { return std::max(result.mi_brake_selected, result.mi_accelerate_selected); }

}  // namespace mm::commonroad
