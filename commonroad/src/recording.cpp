#include "recording.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>

#include "mm/drivable_area.hpp"
#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm::commonroad::detail {

const obstacle* find_obstacle(const scenario& s, std::uint32_t id) {
  for (const obstacle& o : s.obstacles) {
    if (o.id == id) return &o;
  }
  return nullptr;
}

bool is_pedestrian(const obstacle& o) { return o.type == "pedestrian"; }

bool can_be_measured(const obstacle& o) {
  return o.role == obstacle_role::dynamic_obstacle && !is_pedestrian(o) && !o.states.empty();
}

double step_time(const scenario& s, std::int64_t step) { return static_cast<double>(step) * s.time_step; }

const state* state_at(const obstacle& o, std::int64_t step) {
  if (o.states.empty()) return nullptr;
  const std::int64_t first = o.states.front().step;
  if (step < first) return nullptr;
  // Unsigned: no overflow whatever steps a file gives.
  const std::uint64_t index = static_cast<std::uint64_t>(step) - static_cast<std::uint64_t>(first);
  if (index >= o.states.size()) return nullptr;
  return &o.states[static_cast<std::size_t>(index)];
}

const obstacle& measured(const scenario& s, std::uint32_t agent) {
  const obstacle* o = find_obstacle(s, agent);
  const auto error = [&](const std::string& why) {
    return measure_error("road user " + std::to_string(agent) + ": " + why +
                         "; the road users the planner can take the place of (measure, replay) are: " + measurable_road_users_text(s));
  };
  if (o == nullptr) throw error("no obstacle has this id");
  if (o->role == obstacle_role::static_obstacle) throw error("a static obstacle (" + o->type + ")");
  if (is_pedestrian(*o)) throw error("a pedestrian: the planner's ego is a vehicle that steers along arcs (spec §3)");
  return *o;
}

observation observed(const scenario& s, const state& x) {
  return {step_time(s, x.step), pose{x.position, wrap_angle(x.orientation)}, std::max(x.velocity, 0.0)};
}

double largest_speed(const obstacle& o) {
  double v = 0.0;
  for (const state& x : o.states) v = std::max(v, x.velocity);
  return v;
}

std::vector<vec2> circle_polygon(double radius) {
  constexpr std::size_t sides = 16;
  const double vertex_radius = radius / std::cos(std::numbers::pi / static_cast<double>(sides));
  std::vector<vec2> vertices;
  for (std::size_t k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(sides);
    vertices.push_back(vertex_radius * unit_vector(angle));
  }
  return vertices;
}

}  // namespace mm::commonroad::detail

namespace mm::commonroad {

std::vector<vec2> world_polygon(const footprint& shape, const state& x) {
  if (const auto* d = std::get_if<disc>(&shape)) {
    std::vector<vec2> corners = detail::circle_polygon(d->radius);
    for (vec2& corner : corners) corner = x.position + corner;
    return corners;
  }
  const placed_footprint placed = place(shape, pose{x.position, x.orientation});
  return {placed.vertices.begin(), placed.vertices.begin() + static_cast<std::ptrdiff_t>(placed.vertex_count)};
}

bool is_date(std::string_view text) {
  const auto digits = [&](std::size_t from, std::size_t count) {
    int value = 0;
    for (std::size_t i = from; i < from + count; ++i) {
      if (text[i] < '0' || text[i] > '9') return -1;
      value = 10 * value + (text[i] - '0');
    }
    return value;
  };
  if (text.size() != 10 || text[4] != '-' || text[7] != '-' || digits(0, 4) < 0) return false;
  const int month = digits(5, 2);
  const int day = digits(8, 2);
  return month >= 1 && month <= 12 && day >= 1 && day <= 31;
}

drivable_outline lanelet_polygons(const scenario& s) {
  drivable_outline outline;
  for (const lanelet& l : s.lanelets) {
    std::vector<vec2> polygon = l.left_bound;
    polygon.insert(polygon.end(), l.right_bound.rbegin(), l.right_bound.rend());
    if (auto why = drivable_area_error({polygon})) {
      throw std::invalid_argument("lanelet " + std::to_string(l.id) + ": its bounds cannot be part of a drivable area: " +
                                  why->substr(why->find(' ') + 1));
    }
    const std::size_t i = outline.polygons.size();
    outline.open_edges.push_back({i, l.left_bound.size() - 1});  // its end: the left bound's last point to the right's
    outline.open_edges.push_back({i, polygon.size() - 1});       // its start: the right bound's first to the left's
    outline.polygons.push_back(std::move(polygon));
  }
  if (outline.empty()) throw std::invalid_argument("the file has no lanelet: no drivable area can be made of its lanes");
  return outline;
}

}  // namespace mm::commonroad
