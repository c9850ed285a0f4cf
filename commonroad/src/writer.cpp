#include "mm/commonroad/writer.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <variant>

#include "mm/commonroad/reader.hpp"

namespace mm::commonroad {
namespace {

void add_text(pugi::xml_node parent, const char* name, const std::string& text) {
  parent.append_child(name).text().set(text.c_str());
}

/// `value` as the shortest fixed-point text that reads back as the same double ("0.00001", not
/// "1e-05"): the schema's numbers are `xs:decimal`, which has no exponent.
std::string decimal_text(double value) {
  std::array<char, 400> buffer{};  // the longest, -2^-1074 written out, has 327 characters
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed).ptr;
  return std::string(buffer.data(), end);
}

void add_number(pugi::xml_node parent, const char* name, double value) { add_text(parent, name, decimal_text(value)); }

/// `<name><exact>value</exact></name>`.
void add_exact(pugi::xml_node parent, const char* name, const std::string& value) {
  add_text(parent.append_child(name), "exact", value);
}

void add_point(pugi::xml_node parent, vec2 p) {
  pugi::xml_node point = parent.append_child("point");
  add_number(point, "x", p.x);
  add_number(point, "y", p.y);
}

/// A state's elements in the 2020a order: position, orientation, time, velocity, acceleration, yaw
/// rate. `velocity`: written (dynamic obstacles, planning problems), or only when not 0 (static).
void add_state(pugi::xml_node node, const state& x, bool velocity) {
  add_point(node.append_child("position"), x.position);
  add_exact(node, "orientation", decimal_text(x.orientation));
  add_exact(node, "time", std::to_string(x.step));
  if (velocity || x.velocity != 0.0) add_exact(node, "velocity", decimal_text(x.velocity));
  if (x.acceleration) add_exact(node, "acceleration", decimal_text(*x.acceleration));
  if (x.yaw_rate) add_exact(node, "yawRate", decimal_text(*x.yaw_rate));
}

/// A planning problem's initial state, whose elements the schema requires all of: position,
/// velocity, orientation, yaw rate (`as_written` gives every one), slip angle (0: not read), time,
/// and the acceleration when `x` has one.
void add_initial_state(pugi::xml_node node, const state& x) {
  add_point(node.append_child("position"), x.position);
  add_exact(node, "velocity", decimal_text(x.velocity));
  add_exact(node, "orientation", decimal_text(x.orientation));
  add_exact(node, "yawRate", decimal_text(*x.yaw_rate));
  add_exact(node, "slipAngle", "0.0");
  add_exact(node, "time", std::to_string(x.step));
  if (x.acceleration) add_exact(node, "acceleration", decimal_text(*x.acceleration));
}

void add_shape(pugi::xml_node node, const footprint& shape) {
  pugi::xml_node s = node.append_child("shape");
  std::visit(
      [&](const auto& f) {
        using shape_type = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<shape_type, rectangle>) {
          pugi::xml_node r = s.append_child("rectangle");
          add_number(r, "length", f.length);
          add_number(r, "width", f.width);
        } else if constexpr (std::is_same_v<shape_type, disc>) {
          add_number(s.append_child("circle"), "radius", f.radius);
        } else {
          pugi::xml_node polygon = s.append_child("polygon");
          for (const vec2 v : f.vertices) add_point(polygon, v);
        }
      },
      shape);
}

/// The last step any obstacle or planning problem is recorded at.
std::int64_t last_step(const scenario& s) {
  std::int64_t last = 0;
  for (const obstacle& o : s.obstacles) {
    for (const state& x : o.states) last = std::max(last, x.step);
  }
  for (const planning_problem& p : s.planning_problems) last = std::max(last, p.initial.step);
  return last;
}

}  // namespace

scenario as_written(scenario s) {
  s.version = "2020a";
  if (s.date.empty()) s.date = undated;
  std::stable_partition(s.obstacles.begin(), s.obstacles.end(),
                        [](const obstacle& o) { return o.role == obstacle_role::static_obstacle; });
  for (planning_problem& p : s.planning_problems) {
    if (!p.initial.yaw_rate) p.initial.yaw_rate = 0.0;
  }
  return s;
}

std::string scenario_xml(const scenario& given) {
  if (!given.date.empty() && !is_date(given.date)) {
    throw std::invalid_argument("scenario_xml: date '" + given.date + "': expected YYYY-MM-DD or none");
  }
  // Written in the form that reads back: its date, the schema's order of obstacles, and so on.
  const scenario s = as_written(given);
  pugi::xml_document document;
  pugi::xml_node declaration = document.append_child(pugi::node_declaration);
  declaration.append_attribute("version") = "1.0";
  declaration.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = document.append_child("commonRoad");
  root.append_attribute("commonRoadVersion") = "2020a";
  root.append_attribute("benchmarkID") = s.benchmark_id.c_str();
  root.append_attribute("date") = s.date.c_str();
  root.append_attribute("author") = "maneuvermap";
  root.append_attribute("affiliation") = "";
  root.append_attribute("source") = "maneuvermap";
  root.append_attribute("timeStepSize") = decimal_text(s.time_step).c_str();
  // CommonRoad's values for an unknown place (GeoNames id -999, latitude and longitude 999).
  pugi::xml_node location = root.append_child("location");
  add_text(location, "geoNameId", "-999");
  add_text(location, "gpsLatitude", "999.0");
  add_text(location, "gpsLongitude", "999.0");
  root.append_child("scenarioTags");
  for (const lanelet& l : s.lanelets) {
    pugi::xml_node node = root.append_child("lanelet");
    node.append_attribute("id") = l.id;
    pugi::xml_node left = node.append_child("leftBound");
    for (const vec2 p : l.left_bound) add_point(left, p);
    pugi::xml_node right = node.append_child("rightBound");
    for (const vec2 p : l.right_bound) add_point(right, p);
    for (const std::uint32_t id : l.predecessors) node.append_child("predecessor").append_attribute("ref") = id;
    for (const std::uint32_t id : l.successors) node.append_child("successor").append_attribute("ref") = id;
    add_text(node, "laneletType", "unknown");
  }
  for (const obstacle& o : s.obstacles) {
    const bool dynamic = o.role == obstacle_role::dynamic_obstacle;
    pugi::xml_node node = root.append_child(dynamic ? "dynamicObstacle" : "staticObstacle");
    node.append_attribute("id") = o.id;
    add_text(node, "type", o.type);
    add_shape(node, o.shape);
    if (o.states.empty()) continue;  // the reader names it
    add_state(node.append_child("initialState"), o.states.front(), dynamic);
    if (o.states.size() > 1) {
      pugi::xml_node trajectory = node.append_child("trajectory");
      for (std::size_t k = 1; k < o.states.size(); ++k) add_state(trajectory.append_child("state"), o.states[k], dynamic);
    }
  }
  const std::int64_t end = last_step(s);
  for (const planning_problem& p : s.planning_problems) {
    pugi::xml_node node = root.append_child("planningProblem");
    node.append_attribute("id") = p.id;
    add_initial_state(node.append_child("initialState"), p.initial);
    pugi::xml_node time = node.append_child("goalState").append_child("time");
    add_text(time, "intervalStart", std::to_string(p.initial.step));
    add_text(time, "intervalEnd", std::to_string(std::max(end, p.initial.step)));
  }
  std::ostringstream out;
  document.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  std::string text = out.str();
  // The text must read back as `s`: the reader's checks are the contract.
  scenario back;
  try {
    back = read_scenario_text(text, "scenario_xml(" + s.benchmark_id + ")");
  } catch (const read_error& e) {
    throw std::invalid_argument(std::string("scenario_xml: the scenario is not one a CommonRoad file can state: ") + e.what());
  }
  if (!(back == s)) throw std::invalid_argument("scenario_xml: the scenario does not read back as itself");
  return text;
}

void write_scenario(const scenario& s, const std::filesystem::path& file) {
  const std::string text = scenario_xml(s);
  const auto fail = [&] {
    throw std::filesystem::filesystem_error("cannot write the CommonRoad file", file,
                                            std::error_code(errno, std::generic_category()));
  };
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) fail();
  out << text;
  out.close();
  if (!out) fail();
}

}  // namespace mm::commonroad
