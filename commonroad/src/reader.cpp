#include "mm/commonroad/reader.hpp"

#include "recording.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ios>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <variant>
#include <vector>

namespace mm::commonroad {
namespace {

/// Steps beyond this are rejected, so that step arithmetic cannot overflow.
constexpr std::int64_t max_step = std::numeric_limits<std::int32_t>::max();
constexpr std::string_view one_shape = "one <rectangle>, <circle> or <polygon>";

std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

/// `s` without one leading '+' (XML Schema numbers may have one, `std::from_chars` takes none).
std::string_view without_plus(std::string_view s) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
  return s;
}

/// The trimmed text as a finite number; nothing for trailing garbage, "nan", "inf" or overflow.
std::optional<double> to_number(std::string_view text) {
  const std::string_view s = without_plus(trim(text));
  double value = 0.0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (error != std::errc{} || end != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

template <class integer>
std::optional<integer> to_integer(std::string_view text) {
  const std::string_view s = without_plus(trim(text));
  integer value = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (error != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return value;
}

/// `text` for messages: control bytes escaped, cut after 60 bytes.
std::string escaped(std::string_view text) {
  constexpr std::size_t max_shown = 60;
  constexpr char hex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += text[i];
    }
  }
  if (text.size() > max_shown) out += "…";
  return out;
}

/// The helpers below append to a string: `"literal" + std::string` trips GCC 12's -Wrestrict.
std::string enclosed(char open, std::string_view text, char close) {
  std::string out(1, open);
  out += escaped(text);
  out += close;
  return out;
}
std::string quote(std::string_view text) { return enclosed('\'', trim(text), '\''); }
std::string tag(std::string_view name) { return enclosed('<', name, '>'); }
std::string sub(const std::string& path, std::string_view child) { return path + " / " + std::string(child); }

pugi::xml_node next_element(pugi::xml_node n) {
  while (n && n.type() != pugi::node_element) n = n.next_sibling();
  return n;
}
pugi::xml_node first_element(pugi::xml_node parent) { return next_element(parent.first_child()); }

class reader {
 public:
  reader(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  scenario read() const {
    pugi::xml_document document;
    const pugi::xml_parse_result parsed = document.load_buffer(text_.empty() ? "" : text_.data(), text_.size(),
                                                               pugi::parse_default, pugi::encoding_utf8);
    if (!parsed) {
      if (text_.find_first_not_of(" \t\r\n") == std::string_view::npos) {
        throw read_error(location(std::ptrdiff_t{0}) + "not well-formed XML: the file is empty; expected a <commonRoad> document");
      }
      // pugixml reports an element left open by the end of the text at its last byte: a file cut short.
      if (parsed.offset + 1 >= static_cast<std::ptrdiff_t>(text_.size())) {
        throw read_error(location(parsed.offset) + "not well-formed XML: the file ends inside the document (" +
                         parsed.description() + "); is it cut short?");
      }
      throw read_error(location(parsed.offset) + "not well-formed XML: " + parsed.description());
    }
    const pugi::xml_node root = document.document_element();
    if (std::string_view(root.name()) != "commonRoad") {
      fail(root, "document element", tag(root.name()), "<commonRoad>");
    }
    scenario result;
    result.version = trim(attribute(root, "commonRoadVersion", "commonRoad", "2018b or 2020a"));
    if (result.version != "2018b" && result.version != "2020a") {
      fail(root, "commonRoad / commonRoadVersion", quote(result.version), "2018b or 2020a");
    }
    constexpr std::string_view step_size = "a positive finite number of seconds";
    const std::string_view step_text = attribute(root, "timeStepSize", "commonRoad", step_size);
    const std::optional<double> step = to_number(step_text);
    if (!step || *step <= 0.0) fail(root, "commonRoad / timeStepSize", quote(step_text), step_size);
    result.time_step = *step;
    result.benchmark_id = trim(root.attribute("benchmarkID").value());
    if (const std::string_view date = trim(root.attribute("date").value()); is_date(date)) result.date = date;

    std::unordered_map<std::uint32_t, pugi::xml_node> obstacle_ids;
    std::unordered_map<std::uint32_t, pugi::xml_node> problem_ids;
    for (pugi::xml_node n = first_element(root); n; n = next_element(n.next_sibling())) {
      const std::string_view name = n.name();
      if (name == "lanelet") {
        result.lanelets.push_back(read_lanelet(n));
      } else if (name == "dynamicObstacle" || name == "staticObstacle" || name == "obstacle") {
        result.obstacles.push_back(read_obstacle(n));
        unique(obstacle_ids, result.obstacles.back().id, n, "obstacle");
      } else if (name == "planningProblem") {
        result.planning_problems.push_back(read_planning_problem(n));
        unique(problem_ids, result.planning_problems.back().id, n, "planning problem");
      }
    }
    return result;
  }

 private:
  /// The 1-based line of byte `offset`; none when pugixml could not tell the offset.
  std::optional<std::ptrdiff_t> line(std::ptrdiff_t offset) const {
    if (offset < 0) return std::nullopt;
    const auto end = text_.begin() + static_cast<std::ptrdiff_t>(std::min(static_cast<std::size_t>(offset), text_.size()));
    return 1 + std::count(text_.begin(), end, '\n');
  }
  std::optional<std::ptrdiff_t> line(pugi::xml_node n) const { return line(n ? n.offset_debug() : std::ptrdiff_t{-1}); }

  template <class where>
  std::string location(where at) const {
    const auto l = line(at);
    return std::string(source_) + (l ? ":" + std::to_string(*l) : std::string()) + ": ";
  }

  /// Throws "SOURCE:LINE: PATH: FOUND: expected EXPECTED" at the line of `at`.
  [[noreturn]] void fail(pugi::xml_node at, const std::string& path, std::string_view found,
                         std::string_view expected) const {
    throw read_error(location(at) + path + ": " + std::string(found) + ": expected " + std::string(expected));
  }

  std::string_view attribute(pugi::xml_node n, const char* name, const std::string& path,
                             std::string_view expected) const {
    const pugi::xml_attribute a = n.attribute(name);
    if (!a) fail(n, sub(path, name), "missing", expected);
    return a.value();
  }

  /// The `id` attribute; `zero_allowed` for lanelets (the inD conversions have a lanelet 0).
  std::uint32_t read_id(pugi::xml_node n, const std::string& path, bool zero_allowed = false) const {
    const std::string_view expected =
        zero_allowed ? "a non-negative integer id below 2^32" : "a positive integer id below 2^32";
    const std::string_view text = attribute(n, "id", path, expected);
    const std::optional<std::uint64_t> id = to_integer<std::uint64_t>(text);
    if (!id || (*id == 0 && !zero_allowed) || *id > std::numeric_limits<std::uint32_t>::max()) {
      fail(n, sub(path, "id"), quote(text), expected);
    }
    return static_cast<std::uint32_t>(*id);
  }

  /// The lanelet id of a link's `ref` (the lanelet need not be in the file).
  std::uint32_t read_ref(pugi::xml_node n, const std::string& path) const {
    constexpr std::string_view expected = "a lanelet id, a non-negative integer below 2^32";
    const std::string_view text = attribute(n, "ref", path, expected);
    const std::optional<std::uint64_t> id = to_integer<std::uint64_t>(text);
    if (!id || *id > std::numeric_limits<std::uint32_t>::max()) fail(n, sub(path, "ref"), quote(text), expected);
    return static_cast<std::uint32_t>(*id);
  }

  void unique(std::unordered_map<std::uint32_t, pugi::xml_node>& seen, std::uint32_t id, pugi::xml_node n,
              std::string_view what) const {
    const auto [it, inserted] = seen.emplace(id, n);
    if (inserted) return;
    const auto first = line(it->second);
    fail(n, std::string(n.name()) + " " + std::to_string(id) + " / id", quote(std::to_string(id)),
         "an id no other " + std::string(what) + " has (" + it->second.name() + " " + std::to_string(id) +
             (first ? " at line " + std::to_string(*first) : std::string()) + " has it)");
  }

  /// The number in element `e`; `positive` also rejects values ≤ 0.
  double number(pugi::xml_node e, const std::string& path, std::string_view expected, bool positive = false) const {
    const std::string_view text = e.text().get();
    const std::optional<double> value = to_number(text);
    if (!value || (positive && *value <= 0.0)) fail(e, path, quote(text), expected);
    return *value;
  }

  double child_number(pugi::xml_node parent, const char* name, const std::string& path, std::string_view expected,
                      bool positive = false) const {
    const pugi::xml_node e = parent.child(name);
    if (!e) fail(parent, sub(path, name), "missing", expected);
    return number(e, sub(path, name), expected, positive);
  }

  vec2 read_point(pugi::xml_node point, const std::string& path) const {
    const double x = child_number(point, "x", path, "a finite number of metres");
    return {x, child_number(point, "y", path, "a finite number of metres")};
  }

  /// The `<exact>` element of the child `name` of a state; none when that child is absent.
  pugi::xml_node exact(pugi::xml_node state_node, const char* name, const std::string& path) const {
    const pugi::xml_node value = state_node.child(name);
    if (!value) return {};
    if (const pugi::xml_node e = value.child("exact")) return e;
    if (const pugi::xml_node interval = value.child("intervalStart") ? value.child("intervalStart") : value.child("intervalEnd")) {
      fail(interval, sub(path, name), "an interval (" + tag(interval.name()) + ")",
           "<exact>: obstacle states and initial states give exact values");
    }
    fail(value, sub(path, name), "missing", "a value in <exact>");
  }

  std::optional<double> exact_number(pugi::xml_node state_node, const char* name, const std::string& path) const {
    const pugi::xml_node e = exact(state_node, name, path);
    if (!e) return std::nullopt;
    return number(e, sub(path, name), "a finite number in <exact>");
  }

  double required_exact_number(pugi::xml_node state_node, const char* name, const std::string& path,
                               std::string_view why) const {
    const std::optional<double> value = exact_number(state_node, name, path);
    if (!value) fail(state_node, sub(path, name), "missing", "a finite number in <exact>" + std::string(why));
    return *value;
  }

  std::int64_t read_step(pugi::xml_node state_node, const std::string& path) const {
    const std::string expected = "a non-negative integer step (at most " + std::to_string(max_step) + ") in <exact>";
    const pugi::xml_node e = exact(state_node, "time", path);
    if (!e) fail(state_node, sub(path, "time"), "missing", expected);
    const std::string_view text = e.text().get();
    const std::optional<std::int64_t> step = to_integer<std::int64_t>(text);
    if (!step || *step < 0 || *step > max_step) fail(e, sub(path, "time"), quote(text), expected);
    return *step;
  }

  vec2 read_position(pugi::xml_node state_node, const std::string& path) const {
    const std::string field = sub(path, "position");
    constexpr std::string_view expected = "a <point> (only points are supported as positions of obstacle and initial states)";
    const pugi::xml_node position = state_node.child("position");
    if (!position) fail(state_node, field, "missing", expected);
    const pugi::xml_node point = position.child("point");
    if (!point) {
      const pugi::xml_node other = first_element(position);
      if (other) fail(other, field, tag(other.name()), expected);
      fail(position, field, "missing", expected);
    }
    return read_point(point, sub(field, "point"));
  }

  /// An obstacle state or the initial state of a planning problem.
  state read_state(pugi::xml_node n, const std::string& path, bool velocity_required) const {
    state s;
    s.step = read_step(n, path);
    s.position = read_position(n, path);
    s.orientation = required_exact_number(n, "orientation", path, "");
    if (velocity_required) {
      s.velocity = required_exact_number(n, "velocity", path, " (required for dynamic obstacles and planning problems)");
    } else {
      s.velocity = exact_number(n, "velocity", path).value_or(0.0);
    }
    s.yaw_rate = exact_number(n, "yawRate", path);
    s.acceleration = exact_number(n, "acceleration", path);
    return s;
  }

  /// A rectangle or circle at `offset_orientation` and `offset` from the state pose: `exact_shape`
  /// when there is no offset, else the polygon of `vertices` (given in the shape's own frame).
  static footprint offset_shape(const footprint& exact_shape, double offset_orientation, vec2 offset,
                                const std::vector<vec2>& vertices) {
    if (offset_orientation == 0.0 && offset == vec2{}) return exact_shape;
    convex_polygon polygon;
    const double c = std::cos(offset_orientation);
    const double s = std::sin(offset_orientation);
    for (const vec2 v : vertices) polygon.vertices.push_back(offset + rotated(v, c, s));
    return polygon;
  }

  vec2 optional_center(pugi::xml_node shape, const std::string& path) const {
    const pugi::xml_node center = shape.child("center");
    return center ? read_point(center, sub(path, "center")) : vec2{};
  }

  footprint read_shape(pugi::xml_node obstacle_node, const std::string& path) const {
    const std::string field = sub(path, "shape");
    const pugi::xml_node shape = obstacle_node.child("shape");
    if (!shape) fail(obstacle_node, field, "missing", one_shape);
    const pugi::xml_node s = first_element(shape);
    if (!s) fail(shape, field, "missing", one_shape);
    if (const pugi::xml_node second = next_element(s.next_sibling())) {
      fail(second, field, "several shapes (" + tag(s.name()) + " and " + tag(second.name()) + ")", one_shape);
    }
    const std::string_view name = s.name();
    const std::string here = sub(field, name);
    footprint result;
    if (name == "rectangle") {
      constexpr std::string_view size = "a positive finite number of metres";
      const double length = child_number(s, "length", here, size, true);
      const double width = child_number(s, "width", here, size, true);
      const pugi::xml_node orientation = s.child("orientation");
      const double angle = orientation ? number(orientation, sub(here, "orientation"), "a finite angle [rad]") : 0.0;
      const double l = length / 2.0;
      const double w = width / 2.0;
      result = offset_shape(rectangle{length, width}, angle, optional_center(s, here), {{l, -w}, {l, w}, {-l, w}, {-l, -w}});
    } else if (name == "circle") {
      const double radius = child_number(s, "radius", here, "a positive finite number of metres", true);
      result = offset_shape(disc{radius}, 0.0, optional_center(s, here), detail::circle_polygon(radius));
    } else if (name == "polygon") {
      convex_polygon polygon;
      std::size_t index = 0;
      for (pugi::xml_node p = s.child("point"); p; p = p.next_sibling("point")) {
        const vec2 v = read_point(p, sub(here, "point " + std::to_string(++index)));
        if (polygon.vertices.empty() || !(v == polygon.vertices.back())) polygon.vertices.push_back(v);
      }
      if (polygon.vertices.size() > 1 && polygon.vertices.front() == polygon.vertices.back()) polygon.vertices.pop_back();
      result = std::move(polygon);
    } else {
      fail(s, field, "unsupported shape " + tag(name), one_shape);
    }
    if (const std::optional<std::string> error = footprint_error(result)) {
      const auto* polygon = std::get_if<convex_polygon>(&result);
      const std::size_t count = polygon ? polygon->vertices.size() : 0;
      fail(s, here, name == "polygon" ? std::to_string(count) + " distinct vertices" : "an offset " + tag(name),
           "a convex polygon of 3 to " + std::to_string(max_polygon_vertices) + " finite vertices (" + *error + ")");
    }
    return result;
  }

  obstacle read_obstacle(pugi::xml_node n) const {
    obstacle o;
    const std::string name = n.name();
    o.id = read_id(n, name);
    const std::string path = name + " " + std::to_string(o.id);
    if (name == "staticObstacle") {
      o.role = obstacle_role::static_obstacle;
    } else if (name == "obstacle") {
      const pugi::xml_node role = n.child("role");
      const std::string_view text = trim(role.text().get());
      if (!role) fail(n, sub(path, "role"), "missing", "dynamic or static");
      if (text != "dynamic" && text != "static") fail(role, sub(path, "role"), quote(text), "dynamic or static");
      o.role = text == "static" ? obstacle_role::static_obstacle : obstacle_role::dynamic_obstacle;
    }
    const pugi::xml_node type = n.child("type");
    o.type = trim(type.text().get());
    if (o.type.empty()) fail(type ? type : n, sub(path, "type"), type ? "''" : "missing", "the type of road user or obstacle");
    o.shape = read_shape(n, path);

    const bool dynamic = o.role == obstacle_role::dynamic_obstacle;
    const pugi::xml_node initial = n.child("initialState");
    if (!initial) fail(n, sub(path, "initialState"), "missing", "the obstacle's first state");
    o.states.push_back(read_state(initial, sub(path, "initialState"), dynamic));
    if (const pugi::xml_node set = n.child("occupancySet")) {
      fail(set, sub(path, "occupancySet"), "set-based occupancies are not supported", "a <trajectory> of exact states");
    }
    const pugi::xml_node trajectory = n.child("trajectory");
    if (trajectory.child("state") && !dynamic) {
      fail(trajectory, sub(path, "trajectory"), "a trajectory of states", "none in a static obstacle (an empty one is skipped)");
    }
    std::size_t index = 0;
    for (pugi::xml_node s = trajectory.child("state"); s; s = s.next_sibling("state")) {
      const std::string state_path = sub(path, "trajectory / state " + std::to_string(++index));
      const state next = read_state(s, state_path, true);
      const std::int64_t expected = o.states.back().step + 1;
      if (next.step != expected) {
        fail(s.child("time").child("exact"), sub(state_path, "time"), quote(std::to_string(next.step)),
             "step " + std::to_string(expected) + " (trajectory states follow the initial state's step " +
                 std::to_string(o.states.front().step) + " one step apart)");
      }
      o.states.push_back(next);
    }
    return o;
  }

  std::vector<vec2> read_bound(pugi::xml_node lanelet_node, const char* name, const std::string& path) const {
    const std::string field = sub(path, name);
    constexpr std::string_view expected = "a polyline of at least 2 <point>s";
    const pugi::xml_node bound = lanelet_node.child(name);
    if (!bound) fail(lanelet_node, field, "missing", expected);
    std::vector<vec2> points;
    for (pugi::xml_node p = bound.child("point"); p; p = p.next_sibling("point")) {
      points.push_back(read_point(p, sub(field, "point " + std::to_string(points.size() + 1))));
    }
    if (points.size() < 2) fail(bound, field, std::to_string(points.size()) + " point(s)", expected);
    return points;
  }

  lanelet read_lanelet(pugi::xml_node n) const {
    lanelet l;
    l.id = read_id(n, "lanelet", true);
    const std::string path = "lanelet " + std::to_string(l.id);
    l.left_bound = read_bound(n, "leftBound", path);
    l.right_bound = read_bound(n, "rightBound", path);
    for (pugi::xml_node c = first_element(n); c; c = next_element(c.next_sibling())) {
      const std::string_view name = c.name();
      if (name == "predecessor") l.predecessors.push_back(read_ref(c, sub(path, "predecessor")));
      if (name == "successor") l.successors.push_back(read_ref(c, sub(path, "successor")));
    }
    return l;
  }

  planning_problem read_planning_problem(pugi::xml_node n) const {
    planning_problem p;
    p.id = read_id(n, "planningProblem");
    const std::string path = "planningProblem " + std::to_string(p.id) + " / initialState";
    const pugi::xml_node initial = n.child("initialState");
    if (!initial) fail(n, path, "missing", "the ego's initial state");
    p.initial = read_state(initial, path, true);
    return p;
  }

  std::string_view text_;
  std::string_view source_;
};

}  // namespace

scenario read_scenario_text(std::string_view text, std::string_view source) { return reader(text, source).read(); }

scenario read_scenario(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) throw read_error(name + ": is a directory; expected a CommonRoad file (XML)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw read_error(name + ": cannot open the file: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw read_error(name + ": cannot read the file: " + std::strerror(errno));
  return read_scenario_text(text.str(), name);
}

}  // namespace mm::commonroad
