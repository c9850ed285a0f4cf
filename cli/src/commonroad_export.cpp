#include "mm/cli/commonroad_export.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mm/cli/commands.hpp"
#include "mm/sim/roundabout.hpp"

namespace mm::cli {

commonroad_recording::commonroad_recording(const scenario_file::loaded_scenario& loaded, double time_step)
    : loaded_(&loaded), time_step_(time_step), stride_(0) {
  const double dt = loaded.scenario.time_step;
  const double ratio = time_step / dt;
  const double whole = std::round(ratio);
  if (!(std::isfinite(ratio) && whole >= 1.0 && std::abs(ratio - whole) <= 1e-9 * whole && whole <= 1e7)) {
    throw input_error("--commonroad-step " + fixed(time_step, 6) + ": expected a whole multiple of the run's time step " +
                      fixed(dt, 6) + " s");
  }
  stride_ = static_cast<std::size_t>(whole);
}

void commonroad_recording::record(const mm::sim::simulation& now) {
  if (!started_) {
    started_ = true;
    for (mm::sim::agent_id id = 0; id < now.agent_count(); ++id) {
      const mm::sim::agent_info& info = now.info(id);
      mm::commonroad::obstacle o;
      o.id = static_cast<std::uint32_t>(id + 1);
      o.shape = info.shape;
      switch (info.kind) {
        case mm::sim::agent_kind::planning_vehicle:
        case mm::sim::agent_kind::scripted_vehicle: o.type = "car"; break;
        case mm::sim::agent_kind::pedestrian: o.type = "pedestrian"; break;
        case mm::sim::agent_kind::static_obstacle:
          o.type = "unknown";
          o.role = mm::commonroad::obstacle_role::static_obstacle;
          break;
      }
      obstacles_.push_back(std::move(o));
      ended_.push_back(false);
    }
  }
  if (now.step_index() % stride_ != 0) return;
  const auto step = static_cast<std::int64_t>(now.step_index() / stride_);
  for (mm::sim::agent_id id = 0; id < now.agent_count(); ++id) {
    mm::commonroad::obstacle& o = obstacles_[id];
    const mm::sim::agent_state& a = now.state(id);
    if (!a.present()) {
      ended_[id] = ended_[id] || !o.states.empty();
      continue;
    }
    if (ended_[id]) continue;
    if (o.role == mm::commonroad::obstacle_role::static_obstacle && !o.states.empty()) continue;
    mm::commonroad::state x;
    x.step = step;
    x.position = a.pose.position;
    x.orientation = a.pose.heading;
    x.velocity = a.speed;
    if (o.role == mm::commonroad::obstacle_role::dynamic_obstacle) {
      x.acceleration = a.acceleration;
      x.yaw_rate = a.speed * a.curvature;
    }
    o.states.push_back(x);
  }
}

mm::commonroad::scenario commonroad_recording::scenario() const {
  mm::commonroad::scenario s;
  std::string name;
  for (const char c : loaded_->scenario.name) {
    if (std::isalnum(static_cast<unsigned char>(c))) name.push_back(c);
  }
  s.benchmark_id = "ZAM_" + (name.empty() ? std::string("Run") : name) + "-1_1_T-1";
  s.version = "2020a";
  s.time_step = time_step_;
  std::uint32_t next_id = static_cast<std::uint32_t>(obstacles_.size() + 1);
  // Each road piece continues the one before it on its road.
  for (const scenario_file::road& r : loaded_->roads) {
    const double half = 0.5 * r.width;
    std::optional<std::size_t> before;
    for (std::size_t i = 0; i + 1 < r.centre_line.size(); ++i) {
      const vec2 a = r.centre_line[i];
      const vec2 b = r.centre_line[i + 1];
      const double length = norm(b - a);
      if (!(length > 0.0)) continue;
      const vec2 left{-(b.y - a.y) / length * half, (b.x - a.x) / length * half};
      mm::commonroad::lanelet piece;
      piece.id = next_id++;
      piece.left_bound = {a + left, b + left};
      piece.right_bound = {a - left, b - left};
      if (before) {
        s.lanelets[*before].successors.push_back(piece.id);
        piece.predecessors.push_back(s.lanelets[*before].id);
      }
      before = s.lanelets.size();
      s.lanelets.push_back(std::move(piece));
    }
  }
  if (loaded_->roundabout) {
    const std::size_t first = s.lanelets.size();
    const std::vector<mm::sim::lane_edges> lanes = scenario_file::lane_network(*loaded_->roundabout);
    for (const mm::sim::lane_edges& lane : lanes) {
      mm::commonroad::lanelet l;
      l.id = next_id++;
      l.left_bound = lane.left;
      l.right_bound = lane.right;
      s.lanelets.push_back(std::move(l));
    }
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      for (const std::size_t next : lanes[i].successors) {
        s.lanelets[first + i].successors.push_back(s.lanelets[first + next].id);
        s.lanelets[first + next].predecessors.push_back(s.lanelets[first + i].id);
      }
    }
  }
  for (const mm::commonroad::obstacle& o : obstacles_) {
    if (!o.states.empty()) s.obstacles.push_back(o);
  }
  for (std::size_t i = 0; i < loaded_->scenario.planning_vehicles.size() && i < obstacles_.size(); ++i) {
    if (!obstacles_[i].states.empty()) s.planning_problems.push_back({obstacles_[i].id, obstacles_[i].states.front()});
  }
  return s;
}

}  // namespace mm::cli
