#include "mm/scenario_file/loader.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "mm/drivable_area.hpp"
#include "mm/number_text.hpp"
#include "mm/scenario_file/builtin.hpp"
#include "mm/sim/meeting.hpp"
#include "reader.hpp"

namespace mm::scenario_file {

scenario_error::scenario_error(std::string source, int line, int column, std::string field, std::string problem)
    : std::runtime_error([&] {
        std::string text = source;
        if (line > 0) text.append(":").append(std::to_string(line)).append(":").append(std::to_string(column));
        text.append(": ");
        // "field = value: expected ..." reads as one phrase; other problems follow "field: ".
        if (!field.empty()) text.append(field).append(problem.rfind("= ", 0) == 0 ? " " : ": ");
        return text.append(problem);
      }()),
      source_(std::move(source)),
      line_(line),
      column_(column),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

mm::drivable_outline road_polygons(const road& r) {
  mm::drivable_outline outline;
  std::vector<std::vector<vec2>>& polygons = outline.polygons;
  const double half = 0.5 * r.width;
  const auto left_of = [](vec2 a, vec2 b) {
    const vec2 d = b - a;
    const double length = norm(d);
    return vec2{-d.y / length, d.x / length};
  };
  std::size_t previous = r.centre_line.size();  // the last point a piece ended at, none yet
  for (std::size_t i = 0; i + 1 < r.centre_line.size(); ++i) {
    const vec2 a = r.centre_line[i];
    const vec2 b = r.centre_line[i + 1];
    if (a == b) continue;
    const vec2 n = half * left_of(a, b);
    if (previous < r.centre_line.size()) {
      const vec2 p = r.centre_line[previous];
      const vec2 m = half * left_of(p, a);
      // The outer side of the bend at a: right of a left turn, left of a right turn.
      // A bend of under a microradian leaves a gap of microns, which the area closes anyway.
      const double turn = cross(a - p, b - a) / (norm(a - p) * norm(b - a));
      if (turn > 1e-6) polygons.push_back({a, a - m, a - n});
      if (turn < -1e-6) polygons.push_back({a, a + n, a + m});
    } else {
      outline.open_edges.push_back({0, 3});  // the start: from a + n to a − n
    }
    polygons.push_back({a - n, b - n, b + n, a + n});
    previous = i;
  }
  if (!polygons.empty()) outline.open_edges.push_back({polygons.size() - 1, 1});  // the end: from b − n to b + n
  return outline;
}

namespace {

using namespace detail;
using mm::sim::path;

constexpr units speed_units{kmh, mps};
constexpr units angle_units{degrees, radians};

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<std::string> without(std::vector<std::string> keys, std::initializer_list<std::string_view> removed) {
  std::erase_if(keys, [&](const std::string& k) { return std::find(removed.begin(), removed.end(), k) != removed.end(); });
  return keys;
}

// --- the keys of every map of the format (docs/scenario-format.md) -------------------------------

const std::vector<std::string> top_keys{"format",     "name",          "description", "parameters", "duration_s",
                                        "time_step_s", "seed",         "sensing_noise", "roundabout", "roads",
                                        "drivable_area", "defaults",   "agents",        "meet"};
const std::vector<std::string> common_agent_keys{"name", "kind", "path", "start_arc_length_m", "start_time_s", "before_start"};
const std::vector<std::string> planning_keys = concat(
    common_agent_keys,
    concat(concat(keys_of("initial_speed", speed_units), keys_of("desired_speed", speed_units)),
           {"desired_speed_profile", "start_lateral_offset_m", "footprint", "limits", "planner", "follower", "avoidance",
            "planning_period_steps"}));
const std::vector<std::string> motion_keys = concat(
    common_agent_keys, concat(keys_of("speed", speed_units), {"speed_profile", "stop"}));
const std::vector<std::string> scripted_keys = concat(motion_keys, {"footprint", "car_following"});
const std::vector<std::string> pedestrian_keys = concat(motion_keys, {"radius_m"});
const std::vector<std::string> static_keys{"name", "kind", "vertices_m"};

enum class agent_kind_index : std::size_t { planning_vehicle, scripted_vehicle, pedestrian, static_obstacle };

/// Where an agent of the file went in the scenario.
struct agent_entry {
  std::string name;
  field node;
  agent_kind_index kind = agent_kind_index::planning_vehicle;
  std::size_t index = 0;  ///< within its kind's list
};

class mapper {
 public:
  mapper(std::string source, const YAML::Node& root, const load_options& options)
      : root_{root, "", ""}, options_(options) {
    ctx_.source = std::move(source);
  }

  loaded_scenario run() {
    if (!root_.node.IsMap()) fail_value(ctx_, root_, "a map of top-level fields, starting with format: " + std::string(format_version));
    const map_view top(ctx_, {root_});
    check_format(top);
    top.allow(top_keys);
    read_parameters(top);
    result_.parameters = ctx_.parameters;

    mm::sim::scenario& s = result_.scenario;
    s.name = read_string(ctx_, top.require("name"));
    if (s.name.empty()) fail_value(ctx_, top.require("name"), "a non-empty name");
    if (auto d = top.get("description")) s.description = read_string(ctx_, *d);
    s.duration = top.quantity_or("duration", {seconds}, s.duration, range::positive);
    s.time_step = top.quantity_or("time_step", {seconds}, s.time_step, range::positive);
    if (auto seed = top.get("seed")) s.seed = read_integer(ctx_, *seed, std::numeric_limits<std::uint64_t>::max());
    if (options_.seed) s.seed = *options_.seed;
    if (top.has("sensing_noise")) read_noise(top.child("sensing_noise"));
    if (auto r = top.get("roundabout")) read_roundabout(*r);
    if (auto r = top.get("roads")) read_roads(*r);
    if (top.has("drivable_area")) read_drivable_area(top.child("drivable_area"));
    if (options_.on_roads) drive_on_roads(top);
    read_defaults(top);
    read_agents(top.require("agents"));
    if (auto m = top.get("meet")) read_meetings(*m);
    if (options_.policy) {
      for (mm::sim::planning_vehicle& v : s.planning_vehicles) v.planner.policy = *options_.policy;
    }
    validate();
    result_.source = ctx_.source;
    return std::move(result_);
  }

 private:
  void check_format(const map_view& top) {
    const auto f = top.get("format");
    if (!f) ctx_.fail(root_.node, "format", "missing required field format: the first key must be format: " + std::string(format_version));
    const std::string value = read_string(ctx_, *f);
    if (value == format_version) return;
    if (value.rfind("maneuvermap-scenario/", 0) == 0) {
      fail_value(ctx_, *f, std::string(format_version) + ": this version of maneuvermap reads only that version");
    }
    fail_value(ctx_, *f, std::string(format_version));
  }

  void read_parameters(const map_view& top) {
    if (auto p = top.get("parameters")) {
      if (!p->node.IsMap()) fail_value(ctx_, *p, "a map of named numbers, e.g. a_kmh: 30");
      for (const auto& entry : p->node) {
        const field key{entry.first, p->path, ""};
        const std::string name = read_string(ctx_, key);
        const bool valid = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                           std::all_of(name.begin(), name.end(), [](char c) {
                             return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                           });
        const field value{entry.second, p->path + "." + name, name};
        if (!valid) ctx_.fail(entry.first, value.path, "a parameter name is letters, digits and _, starting with a letter");
        if (ctx_.find_parameter(name)) ctx_.fail(entry.first, value.path, "duplicate parameter");
        if (value.node.IsScalar() && !value.node.Scalar().empty() && value.node.Scalar()[0] == '$') {
          fail_value(ctx_, value, "a plain number (parameters cannot refer to other parameters)");
        }
        const double v = read_number(ctx_, value, "");
        ctx_.parameters.push_back({name, v, v});
      }
    }
    for (const auto& override_entry : options_.overrides) {
      const std::string& name = override_entry.first;
      const double value = override_entry.second;
      auto it = std::find_if(ctx_.parameters.begin(), ctx_.parameters.end(), [&](const parameter& p) { return p.name == name; });
      if (it == ctx_.parameters.end()) {
        std::vector<std::string> names;
        std::string list;
        for (const parameter& p : ctx_.parameters) {
          names.push_back(p.name);
          list += (list.empty() ? "" : ", ") + p.name;
        }
        const std::string hint = closest(name, names);
        throw scenario_error(ctx_.source, 0, 0, "--set " + name,
                             "unknown parameter" + (hint.empty() ? "" : "; did you mean " + hint + "?") +
                                 (list.empty() ? " (the scenario has no parameters)" : " (the scenario's parameters: " + list + ")"));
      }
      if (!std::isfinite(value)) throw scenario_error(ctx_.source, 0, 0, "--set " + name, "expected a finite number");
      it->value = value;
    }
  }

  void read_noise(const map_view& v) {
    v.allow(concat(concat({"position_sd_m"}, keys_of("heading_sd", angle_units)), keys_of("speed_sd", speed_units)));
    mm::sim::sensing_noise& n = result_.scenario.noise;
    n.position_sd = v.quantity_or("position_sd", {metres}, 0.0, range::noise);
    n.heading_sd = v.quantity_or("heading_sd", angle_units, 0.0, range::non_negative);
    n.speed_sd = v.quantity_or("speed_sd", speed_units, 0.0, range::noise);
  }

  void read_roundabout(const field& f) {
    const map_view v(ctx_, {f});
    v.allow({"center_m", "radius_m", "connection_radius_m", "arms"});
    roundabout_geometry g;
    if (auto c = v.get("center_m")) g.ring.center = read_point(ctx_, *c);
    g.ring.radius = v.quantity_or("radius", {metres}, g.ring.radius, range::positive);
    g.ring.connection_radius = v.quantity_or("connection_radius", {metres}, g.ring.connection_radius, range::positive);
    // Every point of the ring's and the arms' lanes within the paths' bound: an arm reaches at most
    // 2·(R + r) + its straight from the centre.
    constexpr double bound = mm::sim::largest_path_coordinate;
    const double ring_reach = std::max(std::abs(g.ring.center.x), std::abs(g.ring.center.y)) +
                              2.0 * (g.ring.radius + g.ring.connection_radius);
    if (!(ring_reach <= bound)) {
      ctx_.fail(f.node, f.path,
                "center_m, radius_m = " + number_text(g.ring.radius) + " and connection_radius_m = " +
                    number_text(g.ring.connection_radius) + ": expected |center| + 2·(radius + connection_radius) ≤ " +
                    number_text(bound) + " m (the bound of every path's coordinates)");
    }
    const field arms = v.require("arms");
    if (!arms.node.IsMap() || arms.node.size() == 0) fail_value(ctx_, arms, "a map of named arms, e.g. east: {angle_deg: 0}");
    for (const auto& entry : arms.node) {
      const std::string name = read_string(ctx_, {entry.first, arms.path, ""});
      const field arm_field{entry.second, arms.path + "." + name, name};
      for (const named_arm& other : g.arms) {
        if (other.name == name) ctx_.fail(entry.first, arm_field.path, "duplicate arm name");
      }
      const map_view a(ctx_, {arm_field});
      a.allow(concat(keys_of("angle", angle_units), {"lane_offset_m", "straight_length_m"}));
      mm::sim::roundabout_arm arm;
      arm.angle = a.required_quantity("angle", angle_units);
      arm.lane_offset = a.quantity_or("lane_offset", {metres}, arm.lane_offset, range::non_negative);
      arm.straight_length = a.quantity_or("straight_length", {metres}, arm.straight_length, range::positive);
      if (!(ring_reach + arm.straight_length <= bound)) {
        ctx_.fail(arm_field.node, arm_field.path,
                  "straight_length_m = " + number_text(arm.straight_length) + ": expected at most " +
                      number_text(bound - ring_reach) + " m, so that the arm stays within " + number_text(bound) +
                      " m of the origin (the bound of every path's coordinates)");
      }
      try {
        (void)mm::sim::merge_angle(g.ring, arm);
      } catch (const std::invalid_argument& e) {
        ctx_.fail(arm_field.node, arm_field.path, std::string(e.what()) + " (radius_m = " + number_text(g.ring.radius) + ")");
      }
      g.arms.push_back({name, arm});
    }
    result_.roundabout = std::move(g);
  }

  void read_roads(const field& f) {
    for (const field& item : read_list(ctx_, f)) {
      const map_view r(ctx_, {item});
      r.allow({"name", "centre_line_m", "width_m"});
      road out;
      if (auto n = r.get("name")) out.name = read_string(ctx_, *n);
      out.centre_line = read_points(ctx_, r.require("centre_line_m"), 2, 10000);
      out.width = r.quantity_or("width", {metres}, 7.0, range::positive);
      result_.roads.push_back(std::move(out));
    }
  }

  /// `drivable_area:` (spec §5's road constraint): the file's roads, each as wide as its width, and
  /// further polygons, into `scenario::drivable_area`.
  void read_drivable_area(const map_view& area) {
    area.allow({"roads", "roundabout", "polygons_m", "open_edges"});
    std::vector<std::vector<vec2>>& polygons = result_.scenario.drivable_area.polygons;
    if (auto r = area.get("roads"); r && read_bool(ctx_, *r)) {
      if (result_.roads.empty()) {
        fail_value(ctx_, *r, "false, or roads: in the file (the drivable area is made of the roads it lists)");
      }
      for (const road& each : result_.roads) add_to_drivable_area(road_polygons(each));
    }
    if (auto r = area.get("roundabout")) read_roundabout_lanes(*r);
    const std::size_t first_own = polygons.size();
    if (auto p = area.get("polygons_m")) {
      for (const field& item : read_list(ctx_, *p)) {
        std::vector<vec2> polygon = read_points(ctx_, item, 3, mm::largest_drivable_vertex_count);
        std::vector<std::vector<vec2>> alone{polygon};
        if (auto why = mm::drivable_area_error(alone)) {
          fail_value(ctx_, item, "a polygon of at least 3 vertices not all on one line (" + *why + ")");
        }
        polygons.push_back(std::move(polygon));
      }
    }
    if (auto e = area.get("open_edges")) read_open_edges(*e, first_own);
    if (polygons.empty()) {
      fail_value(ctx_, area.self(),
                 "roads: true (with roads: in the file), roundabout: true (with roundabout: in the file) or "
                 "polygons_m: a list of polygons");
    }
  }

  /// `open_edges: [[polygon, edge], ...]`: edges of `polygons_m` (the polygon's index in that list,
  /// the edge from its vertex `edge` to the next) that lead on beyond the map, as a road's ends do.
  void read_open_edges(const field& f, std::size_t first_own) {
    mm::drivable_outline& outline = result_.scenario.drivable_area;
    const std::size_t own = outline.polygons.size() - first_own;
    for (const field& item : read_list(ctx_, f)) {
      if (!item.node.IsSequence() || item.node.size() != 2) {
        fail_value(ctx_, item, "[polygon, edge]: a polygon of polygons_m (from 0) and one of its edges (from 0)");
      }
      const std::vector<field> pair = read_list(ctx_, item);
      if (own == 0) fail_value(ctx_, pair[0], "an index into polygons_m, but it lists no polygons");
      const std::size_t polygon = read_integer(ctx_, pair[0], own - 1);
      const std::size_t vertices = outline.polygons[first_own + polygon].size();
      const std::size_t edge = read_integer(ctx_, pair[1], vertices - 1);
      const mm::polygon_edge open{first_own + polygon, edge};
      if (std::find(outline.open_edges.begin(), outline.open_edges.end(), open) != outline.open_edges.end()) {
        fail_value(ctx_, item, "an edge not listed before");
      }
      outline.open_edges.push_back(open);
    }
  }

  void add_to_drivable_area(mm::drivable_outline piece) {
    mm::drivable_outline& outline = result_.scenario.drivable_area;
    for (const mm::polygon_edge& e : piece.open_edges) outline.open_edges.push_back({outline.polygons.size() + e.polygon, e.edge});
    for (std::vector<vec2>& p : piece.polygons) outline.polygons.push_back(std::move(p));
  }

  /// `--on-roads` (`load_options::on_roads`): the drivable area of `roads: true, roundabout: true`.
  void drive_on_roads(const map_view& top) {
    const auto refuse = [&](const std::string& why) { throw scenario_error(ctx_.source, 0, 0, "--on-roads", why); };
    if (auto own = top.get("drivable_area")) {
      refuse("the scenario gives its own drivable_area: (line " + std::to_string(own->node.Mark().line + 1) +
             "); expected one of the two");
    }
    if (result_.roads.empty() && !result_.roundabout) {
      refuse("the scenario has no roads: and no roundabout: to make a drivable area of");
    }
    for (const road& each : result_.roads) add_to_drivable_area(road_polygons(each));
    if (result_.roundabout) {
      const mm::sim::roundabout& ring = result_.roundabout->ring;
      if (!(default_roundabout_lane_width < mm::sim::widest_lane(ring))) {
        refuse("the roundabout's 3.5 m lanes need radius_m and connection_radius_m above 1.75 m; give the drivable "
               "area in the file (drivable_area: {roundabout: {lane_width_m: W}})");
      }
      add_to_drivable_area(mm::sim::roundabout_lanes(ring, arms_of(*result_.roundabout), default_roundabout_lane_width));
      result_.roundabout->lane_width = default_roundabout_lane_width;
    }
  }

  /// `drivable_area: {roundabout: true}` or `{roundabout: {lane_width_m: W}}`: the lanes of the file's
  /// roundabout, each W wide (3.5 m for `true`; `mm::sim::roundabout_lanes`).
  void read_roundabout_lanes(const field& f) {
    double lane_width = default_roundabout_lane_width;
    field width_field = f;
    if (f.node.IsMap()) {
      const map_view v(ctx_, {f});
      v.allow({"lane_width_m"});
      if (auto w = v.get("lane_width_m")) width_field = *w;
      lane_width = v.quantity_or("lane_width", {metres}, default_roundabout_lane_width, range::positive);
    } else if (!read_bool(ctx_, f)) {
      return;
    }
    if (!result_.roundabout) {
      fail_value(ctx_, f, "false, or a roundabout: block in the file (the drivable area is made of its lanes)");
    }
    const mm::sim::roundabout& ring = result_.roundabout->ring;
    const double widest = mm::sim::widest_lane(ring);
    if (!(lane_width < widest)) {
      fail_value(ctx_, width_field,
                 "a lane width below " + number_text(widest) +
                     " m, twice the smaller of the roundabout's radius_m and connection_radius_m (a lane's inner "
                     "edge would turn inside out)");
    }
    add_to_drivable_area(mm::sim::roundabout_lanes(ring, arms_of(*result_.roundabout), lane_width));
    result_.roundabout->lane_width = lane_width;
  }

  void read_defaults(const map_view& top) {
    if (!top.has("defaults")) return;
    const map_view d = top.child("defaults");
    d.allow({"planning_vehicle", "scripted_vehicle", "pedestrian"});
    const auto layer = [&](std::string_view kind, const std::vector<std::string>& keys) {
      if (auto f = d.get(kind)) {
        map_view(ctx_, {*f}).allow(without(keys, {"name", "kind", "path"}));
        defaults_[std::string(kind)] = *f;
      }
    };
    layer("planning_vehicle", planning_keys);
    layer("scripted_vehicle", scripted_keys);
    layer("pedestrian", pedestrian_keys);
  }

  map_view agent_view(const field& agent, std::string_view kind) const {
    std::vector<field> layers{agent};
    if (auto it = defaults_.find(std::string(kind)); it != defaults_.end()) layers.push_back(it->second);
    return map_view(ctx_, std::move(layers));
  }

  // --- agents ------------------------------------------------------------------------------------

  void read_agents(const field& f) {
    const std::vector<field> items = read_list(ctx_, f);
    if (items.empty()) fail_value(ctx_, f, "at least one agent");
    for (const field& item : items) {
      const map_view first(ctx_, {item});
      const field name_field = first.require("name");
      const std::string name = read_string(ctx_, name_field);
      if (name.empty()) fail_value(ctx_, name_field, "a non-empty name");
      for (const agent_entry& other : agents_) {
        if (other.name == name) fail_value(ctx_, name_field, "a name no other agent has");
      }
      const std::size_t kind = read_choice(ctx_, first.require("kind"),
                                           {"planning_vehicle", "scripted_vehicle", "pedestrian", "static_obstacle"});
      agent_entry entry{name, item, static_cast<agent_kind_index>(kind), 0};
      mm::sim::scenario& s = result_.scenario;
      switch (entry.kind) {
        case agent_kind_index::planning_vehicle:
          entry.index = s.planning_vehicles.size();
          s.planning_vehicles.push_back(read_planning_vehicle(agent_view(item, "planning_vehicle"), name));
          break;
        case agent_kind_index::scripted_vehicle: {
          const map_view v = agent_view(item, "scripted_vehicle");
          v.allow(scripted_keys);
          mm::sim::scripted_vehicle out;
          out.name = name;
          out.motion = read_motion(v);
          out.shape = read_footprint(v);
          if (v.has("car_following")) out.car_following = read_scripted_car_following(v.child("car_following"));
          entry.index = s.scripted_vehicles.size();
          s.scripted_vehicles.push_back(std::move(out));
          break;
        }
        case agent_kind_index::pedestrian: {
          const map_view v = agent_view(item, "pedestrian");
          v.allow(pedestrian_keys);
          mm::sim::pedestrian out;
          out.name = name;
          out.motion = read_motion(v);
          out.radius = v.quantity_or("radius", {metres}, out.radius, range::size);
          entry.index = s.pedestrians.size();
          s.pedestrians.push_back(std::move(out));
          break;
        }
        case agent_kind_index::static_obstacle: {
          first.allow(static_keys);
          entry.index = s.static_obstacles.size();
          const field vertices = first.require("vertices_m");
          std::vector<vec2> points = read_points(ctx_, vertices, 3, mm::max_polygon_vertices);
          if (!(mm::smallest_dimension(mm::convex_polygon{points}) >= smallest_size)) {
            fail_value(ctx_, vertices, "a polygon at least " + number_text(smallest_size) + " m wide in every direction");
          }
          s.static_obstacles.push_back({name, std::move(points)});
          break;
        }
      }
      agents_.push_back(std::move(entry));
    }
  }

  mm::rectangle read_footprint(const map_view& v) const {
    const map_view f = v.child("footprint");
    f.allow({"length_m", "width_m"});
    mm::rectangle r;
    r.length = f.quantity_or("length", {metres}, r.length, range::size);
    r.width = f.quantity_or("width", {metres}, r.width, range::size);
    return r;
  }

  mm::sim::before_start_behaviour read_before_start(const map_view& v) const {
    if (auto f = v.get("before_start")) {
      return read_choice(ctx_, *f, {"absent", "wait"}) == 0 ? mm::sim::before_start_behaviour::absent
                                                            : mm::sim::before_start_behaviour::wait;
    }
    return mm::sim::before_start_behaviour::absent;
  }

  mm::sim::planning_vehicle read_planning_vehicle(const map_view& v, const std::string& name) const {
    v.allow(planning_keys);
    mm::sim::planning_vehicle out;
    out.name = name;
    out.path = read_path(v.require("path"));
    out.start_arc_length = v.quantity_or("start_arc_length", {metres}, 0.0, range::non_negative);
    out.start_lateral_offset = v.quantity_or("start_lateral_offset", {metres}, 0.0);
    out.start_time = v.quantity_or("start_time", {seconds}, 0.0, range::non_negative);
    out.before_start = read_before_start(v);
    out.desired_speed = v.required_quantity("desired_speed", speed_units, range::speed);
    out.initial_speed = v.quantity_or("initial_speed", speed_units, out.desired_speed, range::speed);
    if (auto f = v.get("desired_speed_profile")) out.desired_speed_profile = read_knots(*f);
    out.shape = read_footprint(v);
    out.limits = read_limits(v.child("limits"));
    out.planner = read_planner(v.child("planner"));
    out.follower = read_follower(v.child("follower"));
    if (auto f = v.get("avoidance")) out.avoidance = read_bool(ctx_, *f);
    if (auto f = v.get("planning_period_steps")) {
      out.planning_period = static_cast<std::size_t>(read_integer(ctx_, *f, 1'000'000));
      if (out.planning_period < 1) fail_value(ctx_, *f, "an integer from 1 to 1000000 [steps]");
    }
    return out;
  }

  mm::ego_limits read_limits(const map_view& v) const {
    v.allow(concat({"max_acceleration_mps2", "max_deceleration_mps2", "max_lateral_acceleration_mps2",
                    "min_turning_radius_m", "steering"},
                   keys_of("speed_cap", speed_units)));
    mm::ego_limits l;
    l.max_acceleration = v.quantity_or("max_acceleration", {mps2}, l.max_acceleration, range::positive);
    l.max_deceleration = v.quantity_or("max_deceleration", {mps2}, l.max_deceleration, range::positive);
    l.max_lateral_acceleration = v.quantity_or("max_lateral_acceleration", {mps2}, l.max_lateral_acceleration, range::positive);
    l.min_turning_radius = v.quantity_or("min_turning_radius", {metres}, l.min_turning_radius, range::positive);
    l.speed_cap = v.quantity_or("speed_cap", speed_units, l.speed_cap, range::positive_speed);
    if (auto f = v.get("steering")) l.steering = read_bool(ctx_, *f);
    return l;
  }

  mm::planner_config read_planner(const map_view& v) const {
    v.allow({"policy", "forecast_time_s", "safety_margin_m", "urgent_steering", "displacement_horizon_s",
             "collision_window_s", "forecast_step_s", "forecast_count", "history_window_s", "resolution",
             "max_time_step_s", "effort_weights", "assignment_search", "max_exhaustive_assignments", "map_column"});
    mm::planner_config c;
    if (auto f = v.get("policy")) {
      constexpr std::array kinds{mm::forecast_policy_kind::adjustable, mm::forecast_policy_kind::constant,
                                 mm::forecast_policy_kind::robust};
      c.policy.kind = kinds.at(read_choice(ctx_, *f, {"adj", "const", "robust"}));
    }
    c.policy.constant_forecast_time = v.quantity_or("forecast_time", {seconds}, c.policy.constant_forecast_time, range::non_negative);
    c.safety_margin = v.quantity_or("safety_margin", {metres}, c.safety_margin, range::non_negative);
    if (auto f = v.get("urgent_steering")) c.urgent_steering = read_bool(ctx_, *f);
    c.displacement_horizon = v.quantity_or("displacement_horizon", {seconds}, c.displacement_horizon, range::positive);
    c.collision_window = v.quantity_or("collision_window", {seconds}, c.collision_window, range::positive);
    c.forecast_step = v.quantity_or("forecast_step", {seconds}, c.forecast_step, range::positive);
    if (auto f = v.get("forecast_count")) c.forecast_count = read_integer(ctx_, *f, mm::largest_forecast_count);
    c.history_window = v.quantity_or("history_window", {seconds}, c.history_window, range::positive);
    if (v.has("resolution")) {
      const map_view r = v.child("resolution");
      r.allow({"accelerations", "curvatures"});
      if (auto f = r.get("accelerations")) {
        c.resolution.accelerations = read_integer(ctx_, *f, mm::largest_sampling_side);
      }
      if (auto f = r.get("curvatures")) c.resolution.curvatures = read_integer(ctx_, *f, mm::largest_sampling_side);
    }
    c.max_time_step = v.quantity_or("max_time_step", {seconds}, c.max_time_step, range::positive);
    if (v.has("effort_weights")) {
      const map_view w = v.child("effort_weights");
      w.allow({"longitudinal", "lateral"});
      if (auto f = w.get("longitudinal")) c.effort.longitudinal = read_number(ctx_, *f, "s⁴/m²", range::non_negative);
      if (auto f = w.get("lateral")) c.effort.lateral = read_number(ctx_, *f, "s⁴/m²", range::non_negative);
    }
    if (auto f = v.get("assignment_search")) {
      c.assignment_search = read_choice(ctx_, *f, {"coordinate_ascent", "exhaustive"}) == 0
                                ? mm::assignment_search_kind::coordinate_ascent
                                : mm::assignment_search_kind::exhaustive;
    }
    if (auto f = v.get("max_exhaustive_assignments")) {
      c.max_exhaustive_assignments = read_integer(ctx_, *f, std::numeric_limits<std::uint32_t>::max());
    }
    if (auto f = v.get("map_column")) c.map_column = read_bool(ctx_, *f);
    return c;
  }

  mm::sim::follower_config read_follower(const map_view& v) const {
    v.allow({"lookahead_time_s", "min_lookahead_m", "speed_gain_per_s", "comfortable_deceleration_mps2",
             "curve_lateral_acceleration_mps2", "car_following"});
    mm::sim::follower_config c;
    c.lookahead_time = v.quantity_or("lookahead_time", {seconds}, c.lookahead_time, range::positive);
    c.min_lookahead = v.quantity_or("min_lookahead", {metres}, c.min_lookahead, range::positive);
    c.speed_gain = v.quantity_or("speed_gain", {per_second}, c.speed_gain, range::positive);
    c.comfortable_deceleration = v.quantity_or("comfortable_deceleration", {mps2}, c.comfortable_deceleration, range::positive);
    c.curve_lateral_acceleration = v.quantity("curve_lateral_acceleration", {mps2}, range::positive);
    if (v.has("car_following")) {
      const map_view f = v.child("car_following");
      f.allow(car_following_keys());
      c.car_following = read_car_following(f);
    }
    return c;
  }

  static std::vector<std::string> car_following_keys() {
    return concat({"time_gap_s", "jam_distance_m", "corridor_half_width_m"}, keys_of("max_heading_difference", angle_units));
  }

  mm::sim::car_following_config read_car_following(const map_view& f) const {
    mm::sim::car_following_config k;
    k.time_gap = f.quantity_or("time_gap", {seconds}, k.time_gap, range::non_negative);
    k.jam_distance = f.quantity_or("jam_distance", {metres}, k.jam_distance, range::non_negative);
    k.corridor_half_width = f.quantity_or("corridor_half_width", {metres}, k.corridor_half_width, range::positive);
    k.max_heading_difference =
        f.quantity_or("max_heading_difference", angle_units, k.max_heading_difference, range::non_negative);
    return k;
  }

  /// A scripted vehicle's car following: the planning vehicles' fields and the accelerations that
  /// a planning vehicle takes from its limits and its follower.
  mm::sim::scripted_car_following read_scripted_car_following(const map_view& f) const {
    f.allow(concat(car_following_keys(), {"max_acceleration_mps2", "comfortable_deceleration_mps2",
                                          "max_deceleration_mps2", "speed_gain_per_s", "follows_scripted"}));
    mm::sim::scripted_car_following k;
    k.following = read_car_following(f);
    k.max_acceleration = f.quantity_or("max_acceleration", {mps2}, k.max_acceleration, range::positive);
    k.comfortable_deceleration =
        f.quantity_or("comfortable_deceleration", {mps2}, k.comfortable_deceleration, range::positive);
    k.max_deceleration = f.quantity_or("max_deceleration", {mps2}, k.max_deceleration, range::positive);
    k.speed_gain = f.quantity_or("speed_gain", {per_second}, k.speed_gain, range::positive);
    if (auto b = f.get("follows_scripted")) k.follows_scripted = read_bool(ctx_, *b);
    return k;
  }

  /// A list of knots `{time_s, speed_kmh}` at increasing times.
  mm::sim::speed_profile read_knots(const field& f) const {
    const std::vector<field> knots = read_list(ctx_, f);
    if (knots.empty()) fail_value(ctx_, f, "at least one knot {time_s, speed_kmh}");
    mm::sim::speed_profile profile;
    for (const field& k : knots) {
      const map_view kv(ctx_, {k});
      kv.allow(concat({"time_s"}, keys_of("speed", speed_units)));
      profile.knots.push_back({kv.required_quantity("time", {seconds}, range::non_negative),
                               kv.required_quantity("speed", speed_units, range::speed)});
      if (profile.knots.size() > 1 && !(profile.knots.back().time > profile.knots[profile.knots.size() - 2].time)) {
        fail_value(ctx_, kv.require("time_s"), "a time after the previous knot's");
      }
    }
    return profile;
  }

  mm::sim::scripted_motion read_motion(const map_view& v) const {
    mm::sim::scripted_motion m;
    m.path = read_path(v.require("path"));
    m.start_arc_length = v.quantity_or("start_arc_length", {metres}, 0.0, range::non_negative);
    m.start_time = v.quantity_or("start_time", {seconds}, 0.0, range::non_negative);
    m.before_start = read_before_start(v);
    const std::optional<field> speed = v.one_of({"speed_kmh", "speed_mps", "speed_profile"});
    if (!speed) ctx_.fail(v.self().node, v.self().path, "missing required field speed_kmh, speed_mps or speed_profile");
    if (speed->key == "speed_profile") {
      m.speed = read_knots(*speed);
    } else {
      m.speed = mm::sim::speed_profile::constant(*v.quantity("speed", speed_units, range::speed));
    }
    if (v.has("stop")) {
      const map_view s = v.child("stop");
      s.allow({"arc_length_m", "duration_s"});
      mm::sim::stop_rule stop;
      stop.arc_length = s.required_quantity("arc_length", {metres}, range::non_negative);
      stop.duration = s.quantity("duration", {seconds}, range::positive);
      m.stop = stop;
    }
    return m;
  }

  // --- paths -------------------------------------------------------------------------------------

  mm::pose read_pose(const map_view& v) const {
    v.allow(concat({"position_m"}, keys_of("heading", angle_units)));
    return {read_point(ctx_, v.require("position_m")), v.required_quantity("heading", angle_units)};
  }

  const named_arm& find_arm(const field& f) const {
    const std::string name = read_string(ctx_, f);
    if (!result_.roundabout) fail_value(ctx_, f, "an arm of the scenario's roundabout, but the scenario declares no roundabout:");
    std::vector<std::string> names;
    for (const named_arm& arm : result_.roundabout->arms) {
      if (arm.name == name) return arm;
      names.push_back(arm.name);
    }
    const std::string hint = closest(name, names);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    fail_value(ctx_, f, "an arm of the roundabout (" + list + ")" + (hint.empty() ? "" : "; did you mean " + hint + "?"));
  }

  path read_roundabout_path(const field& f) const {
    const map_view v(ctx_, {f});
    v.allow(concat(concat({"entry", "exit", "extra_laps"}, keys_of("start_angle", angle_units)), keys_of("sweep", angle_units)));
    if (!result_.roundabout) ctx_.fail(f.node, f.path, "a roundabout path needs the top-level roundabout: block");
    const mm::sim::roundabout& ring = result_.roundabout->ring;
    const std::optional<field> entry = v.get("entry");
    const std::optional<double> start_angle = v.quantity("start_angle", angle_units);
    const std::optional<field> exit = v.get("exit");
    const std::optional<double> sweep = v.quantity("sweep", angle_units, range::positive);
    int laps = 0;
    if (auto l = v.get("extra_laps")) {
      if (!exit) ctx_.fail(l->node, l->path, "extra_laps needs an exit");
      laps = static_cast<int>(read_integer(ctx_, *l, 100));
    }
    if (entry.has_value() == start_angle.has_value() || exit.has_value() == sweep.has_value()) {
      ctx_.fail(f.node, f.path, "give entry (an arm) or start_angle_deg (on the ring), and exit (an arm) or sweep_deg");
    }
    if (entry && exit) return mm::sim::roundabout_route(ring, find_arm(*entry).arm, find_arm(*exit).arm, laps);
    if (entry) return mm::sim::roundabout_entry_route(ring, find_arm(*entry).arm, *sweep);
    if (exit) return mm::sim::roundabout_exit_route(ring, *start_angle, find_arm(*exit).arm, laps);
    return mm::sim::roundabout_ring(ring, *start_angle, *sweep);
  }

  path read_path(const field& f) const {
    const map_view v(ctx_, {f});
    v.allow({"start", "polyline_m", "arc", "roundabout", "segments"});
    const std::optional<field> base = v.one_of({"start", "polyline_m", "arc", "roundabout"});
    if (!base) ctx_.fail(f.node, f.path, "missing required field start, polyline_m, arc or roundabout");
    path p;
    try {
      if (base->key == "start") {
        p = path(read_pose(map_view(ctx_, {*base})));
      } else if (base->key == "polyline_m") {
        p = path::polyline(read_points(ctx_, *base, 2, 10000));
      } else if (base->key == "arc") {
        const map_view a(ctx_, {*base});
        a.allow(concat(concat({"center_m", "radius_m"}, keys_of("start_angle", angle_units)), keys_of("sweep", angle_units)));
        p = path::circular_arc(read_point(ctx_, a.require("center_m")), a.required_quantity("radius", {metres}, range::positive),
                               a.required_quantity("start_angle", angle_units), a.required_quantity("sweep", angle_units));
      } else {
        p = read_roundabout_path(*base);
      }
    } catch (const std::invalid_argument& e) {
      ctx_.fail(base->node, base->path, e.what());
    }
    if (auto segments = v.get("segments")) {
      const std::vector<field> items = read_list(ctx_, *segments);
      if (base->key == "start" && items.empty()) fail_value(ctx_, *segments, "at least one segment");
      for (const field& item : items) append_segment(p, item);
    } else if (base->key == "start") {
      ctx_.fail(f.node, f.path, "missing required field segments (a path from a start pose needs segments)");
    }
    return p;
  }

  void append_segment(path& p, const field& item) const {
    const map_view s(ctx_, {item});
    s.allow({"straight_m", "turn", "line_to_m", "curve"});
    if (item.node.size() != 1) {
      fail_value(ctx_, item,
                 "one of straight_m: L, turn: {radius_m, angle_deg}, line_to_m: [x, y], curve: {length_m, curvature_per_m}");
    }
    try {
      if (auto f = s.get("straight_m")) {
        p.straight(read_number(ctx_, *f, "m", range::positive));
      } else if (auto t = s.get("turn")) {
        const map_view tv(ctx_, {*t});
        tv.allow(concat({"radius_m"}, keys_of("angle", angle_units)));
        const double radius = tv.required_quantity("radius", {metres}, range::positive);
        const double angle = tv.required_quantity("angle", angle_units);
        if (angle == 0.0) fail_value(ctx_, *tv.one_of({"angle_deg", "angle_rad"}), "a non-zero angle (positive turns left)");
        p.turn(radius, angle);
      } else if (auto l = s.get("line_to_m")) {
        const vec2 point = read_point(ctx_, *l);
        if (point == p.end_pose().position) fail_value(ctx_, *l, "a point other than the current end of the path");
        p.line_to(point);
      } else if (auto c = s.get("curve")) {
        const map_view cv(ctx_, {*c});
        cv.allow({"length_m", "curvature_per_m"});
        p.curve(cv.required_quantity("length", {metres}, range::positive), cv.required_quantity("curvature", {per_metre}));
      }
    } catch (const std::invalid_argument& e) {
      ctx_.fail(item.node, item.path, e.what());
    }
  }

  // --- meet --------------------------------------------------------------------------------------

  const agent_entry& find_agent(const field& f) const {
    const std::string name = read_string(ctx_, f);
    std::vector<std::string> names;
    for (const agent_entry& a : agents_) {
      if (a.name == name) {
        if (a.kind == agent_kind_index::static_obstacle) fail_value(ctx_, f, "a moving agent; static obstacles do not move");
        return a;
      }
      names.push_back(a.name);
    }
    const std::string hint = closest(name, names);
    fail_value(ctx_, f, "the name of an agent" + (hint.empty() ? std::string() : " (did you mean " + hint + "?)"));
  }

  /// The agent's start time, start arc length, path and constant initial speed.
  struct timing_view {
    double* start_time = nullptr;
    double start_arc_length = 0.0;
    const path* route = nullptr;
    double speed = 0.0;
  };

  timing_view timing_of(const agent_entry& a) {
    mm::sim::scenario& s = result_.scenario;
    switch (a.kind) {
      case agent_kind_index::planning_vehicle: {
        mm::sim::planning_vehicle& v = s.planning_vehicles[a.index];
        return {&v.start_time, v.start_arc_length, &v.path, v.initial_speed};
      }
      case agent_kind_index::scripted_vehicle: {
        mm::sim::scripted_motion& m = s.scripted_vehicles[a.index].motion;
        return {&m.start_time, m.start_arc_length, &m.path, mm::sim::profile_speed(m.speed, 0.0)};
      }
      case agent_kind_index::pedestrian: {
        mm::sim::scripted_motion& m = s.pedestrians[a.index].motion;
        return {&m.start_time, m.start_arc_length, &m.path, mm::sim::profile_speed(m.speed, 0.0)};
      }
      case agent_kind_index::static_obstacle: break;
    }
    return {};
  }

  vec2 read_named_point(const field& f) const {
    const map_view v(ctx_, {f});
    v.allow({"roundabout_merge", "roundabout_diverge"});
    const std::optional<field> which = v.one_of({"roundabout_merge", "roundabout_diverge"});
    if (!which) ctx_.fail(f.node, f.path, "missing required field roundabout_merge or roundabout_diverge (an arm name)");
    const named_arm& arm = find_arm(*which);
    const mm::sim::roundabout& ring = result_.roundabout->ring;
    const double angle = which->key == "roundabout_merge" ? mm::sim::merge_angle(ring, arm.arm) : mm::sim::diverge_angle(ring, arm.arm);
    return mm::sim::ring_point(ring, angle);
  }

  void read_meetings(const field& f) {
    std::vector<mm::sim::meeting> meetings;
    std::vector<const agent_entry*> timed;  // agents in meetings, by meeting index order
    const auto slot = [&](const agent_entry& a) {
      for (std::size_t i = 0; i < timed.size(); ++i) {
        if (timed[i] == &a) return i;
      }
      timed.push_back(&a);
      return timed.size() - 1;
    };
    for (const field& item : read_list(ctx_, f)) {
      const map_view v(ctx_, {item});
      v.allow({"agents", "conflict_point_m", "conflict_point", "distances_m", "lag_s", "timed_along", "tolerance_m"});
      const field names = v.require("agents");
      if (!names.node.IsSequence() || names.node.size() != 2) fail_value(ctx_, names, "a list of two agent names [A, B]");
      const std::vector<field> name_fields = read_list(ctx_, names);
      const agent_entry& first = find_agent(name_fields[0]);
      const agent_entry& second = find_agent(name_fields[1]);
      if (&first == &second) fail_value(ctx_, name_fields[1], "two different agents");
      const double tolerance = v.quantity_or("tolerance", {metres}, 0.05, range::positive);
      const double lag = v.quantity_or("lag", {seconds}, 0.0);

      std::map<std::string, path> along;
      if (auto t = v.get("timed_along")) {
        if (!t->node.IsMap()) fail_value(ctx_, *t, "a map from agent name to the path it is timed along");
        for (const auto& entry : t->node) {
          const field key{entry.first, t->path, ""};
          const std::string name = read_string(ctx_, key);
          if (name != first.name && name != second.name) fail_value(ctx_, key, "one of the two agents " + first.name + ", " + second.name);
          along[name] = read_path({entry.second, t->path + "." + name, name});
        }
      }

      const std::optional<field> where = v.one_of({"conflict_point_m", "conflict_point", "distances_m"});
      if (!where) ctx_.fail(item.node, item.path, "missing required field conflict_point_m, conflict_point or distances_m");
      double distances[2] = {0.0, 0.0};
      const agent_entry* pair[2] = {&first, &second};
      if (where->key == "distances_m") {
        if (!where->node.IsSequence() || where->node.size() != 2) {
          fail_value(ctx_, *where, "two distances [m] from each agent's start to the conflict point");
        }
        for (int i = 0; i < 2; ++i) distances[i] = read_number(ctx_, {where->node[i], where->path + "[" + std::to_string(i) + "]", where->key}, "m", range::non_negative);
      } else {
        const vec2 point = where->key == "conflict_point_m" ? read_point(ctx_, *where) : read_named_point(*where);
        for (int i = 0; i < 2; ++i) {
          const timing_view t = timing_of(*pair[i]);
          const auto it = along.find(pair[i]->name);
          const path& route = it != along.end() ? it->second : *t.route;
          try {
            distances[i] = mm::sim::arc_length_at(route, point, tolerance) - t.start_arc_length;
          } catch (const std::invalid_argument& e) {
            ctx_.fail(where->node, where->path, "agent " + pair[i]->name + ": " + e.what());
          }
          if (distances[i] < 0.0) {
            ctx_.fail(where->node, where->path, "the conflict point lies " + number_text(-distances[i]) +
                                                    " m behind the start of agent " + pair[i]->name);
          }
        }
      }
      double travel[2] = {0.0, 0.0};
      for (int i = 0; i < 2; ++i) {
        try {
          travel[i] = mm::sim::travel_time(distances[i], timing_of(*pair[i]).speed);
        } catch (const std::invalid_argument& e) {
          ctx_.fail(item.node, item.path, "agent " + pair[i]->name + ": " + e.what());
        }
      }
      meetings.push_back({slot(first), slot(second), travel[0], travel[1], lag});
      result_.meetings.push_back({first.name, second.name, distances[0], distances[1], travel[0], travel[1], lag, 0.0, 0.0});
    }
    std::vector<double> starts;
    for (const agent_entry* a : timed) starts.push_back(*timing_of(*a).start_time);
    std::vector<double> solved;
    try {
      solved = mm::sim::meeting_start_times(starts, meetings);
    } catch (const std::invalid_argument& e) {
      ctx_.fail(f.node, f.path, e.what());
    }
    for (std::size_t i = 0; i < timed.size(); ++i) *timing_of(*timed[i]).start_time = solved[i];
    for (std::size_t k = 0; k < meetings.size(); ++k) {
      result_.meetings[k].first_start = solved[meetings[k].first];
      result_.meetings[k].second_start = solved[meetings[k].second];
    }
  }

  // --- semantic checks ---------------------------------------------------------------------------

  void validate() const {
    const std::optional<std::string> error = mm::sim::validation_error(result_.scenario);
    if (!error) return;
    // "planning_vehicles[0] \"A\": field = value: expected ..." — point at the agent's entry.
    const std::size_t open = error->find('"');
    const std::size_t close = open == std::string::npos ? open : error->find("\": ", open + 1);
    if (close != std::string::npos) {
      const std::string name = error->substr(open + 1, close - open - 1);
      // A policy the command line gave every vehicle is the command line's error, not the file's.
      if (options_.policy && error->find("planner.policy", close) == close + 3) {
        throw scenario_error(ctx_.source, 0, 0, "--policy " + policy_name(*options_.policy),
                             error->substr(close + 3) + " (for planning vehicle " + name + "; the simulator's field names)");
      }
      for (std::size_t i = 0; i < agents_.size(); ++i) {
        if (agents_[i].name == name) {
          ctx_.fail(agents_[i].node.node, agents_[i].node.path + " \"" + name + "\"", error->substr(close + 3) +
                                                                                         " (the simulator's field names, SI units)");
        }
      }
    }
    const std::string prefix = "scenario: ";
    ctx_.fail(root_.node, "", error->rfind(prefix, 0) == 0 ? error->substr(prefix.size()) : *error);
  }

  context ctx_;
  field root_;
  const load_options& options_;
  loaded_scenario result_;
  std::map<std::string, field> defaults_;
  std::vector<agent_entry> agents_;
};

}  // namespace

std::vector<mm::sim::roundabout_arm> arms_of(const roundabout_geometry& g) {
  std::vector<mm::sim::roundabout_arm> arms;
  for (const named_arm& each : g.arms) arms.push_back(each.arm);
  return arms;
}

std::vector<mm::sim::lane_edges> lane_network(const roundabout_geometry& g) {
  const double widest = mm::sim::widest_lane(g.ring);
  double width = g.lane_width.value_or(default_roundabout_lane_width);
  if (!(width < widest)) width = 0.5 * widest;
  return mm::sim::roundabout_lane_edges(g.ring, arms_of(g), width);
}

loaded_scenario load_text(std::string_view text, const std::string& source, const load_options& options) {
  YAML::Node root;
  try {
    root.reset(YAML::Load(std::string(text)));
  } catch (const YAML::DeepRecursion& e) {
    throw scenario_error(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, e.mark.column >= 0 ? e.mark.column + 1 : 0, "",
                         "malformed YAML: nested " + std::to_string(e.depth()) +
                             " levels deep, deeper than the YAML reader goes (a scenario file nests a few levels)");
  } catch (const YAML::Exception& e) {
    const int line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
    const int column = e.mark.column >= 0 ? e.mark.column + 1 : 0;
    throw scenario_error(source, line, column, "", "malformed YAML: " + e.msg);
  }
  try {
    return mapper(source, root, options).run();
  } catch (const YAML::Exception& e) {
    const int line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
    throw scenario_error(source, line, e.mark.column >= 0 ? e.mark.column + 1 : 0, "", e.msg);
  }
}

loaded_scenario load_file(const std::filesystem::path& file, const load_options& options) {
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) {
    throw scenario_error(file.string(), 0, 0, "", "is a directory; expected a scenario file (YAML)");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw scenario_error(file.string(), 0, 0, "", std::string("cannot read the file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw scenario_error(file.string(), 0, 0, "", std::string("cannot read the file: ") + std::strerror(errno));
  return load_text(text.str(), file.string(), options);
}

loaded_scenario load(std::string_view file_or_builtin, const load_options& options) {
  const std::string arg(file_or_builtin);
  const auto ends_with = [&](std::string_view suffix) {
    return arg.size() >= suffix.size() && arg.compare(arg.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  const bool looks_like_path = arg.find('/') != std::string::npos || ends_with(".yaml") || ends_with(".yml");
  if (!looks_like_path) {
    if (const builtin_scenario* b = find_builtin(arg)) return load_text(b->text, "builtin:" + arg, options);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(arg, ec)) {
      std::vector<std::string> names;
      for (const builtin_scenario& b : builtin_scenarios()) names.emplace_back(b.name);
      const std::string hint = closest(arg, names);
      throw scenario_error(arg, 0, 0, "",
                           "no such file or built-in scenario" +
                               (hint.empty() ? std::string() : "; did you mean " + hint + "?") +
                               " (`maneuvermap list` shows the built-in scenarios)");
    }
  }
  return load_file(arg, options);
}

std::optional<mm::forecast_policy> parse_policy(std::string_view text) {
  if (text == "adj") return mm::forecast_policy{mm::forecast_policy_kind::adjustable, 1.0};
  if (text == "robust") return mm::forecast_policy{mm::forecast_policy_kind::robust, 1.0};
  constexpr std::string_view prefix = "const:";
  if (text.substr(0, prefix.size()) != prefix) return std::nullopt;
  const std::string_view number = text.substr(prefix.size());
  double tau = 0.0;
  const auto r = std::from_chars(number.data(), number.data() + number.size(), tau);
  if (number.empty() || r.ec != std::errc() || r.ptr != number.data() + number.size() || !std::isfinite(tau) || tau < 0.0) {
    return std::nullopt;
  }
  return mm::forecast_policy{mm::forecast_policy_kind::constant, tau};
}

std::string policy_name(const mm::forecast_policy& policy) {
  if (policy.kind == mm::forecast_policy_kind::adjustable) return "adj";
  if (policy.kind == mm::forecast_policy_kind::robust) return "robust";
  return "const:" + number_text(policy.constant_forecast_time);
}

std::string closest_name(std::string_view word, const std::vector<std::string>& candidates) {
  return closest(word, candidates);
}

std::string unknown_key_hint(std::string_view word, const std::vector<std::string>& candidates) {
  return detail::unknown_name_hint(word, candidates);
}

std::optional<std::pair<std::string, double>> parse_override(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) return std::nullopt;
  const std::string_view number = text.substr(eq + 1);
  double value = 0.0;
  const auto r = std::from_chars(number.data(), number.data() + number.size(), value);
  if (number.empty() || r.ec != std::errc() || r.ptr != number.data() + number.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return std::pair{std::string(text.substr(0, eq)), value};
}

}  // namespace mm::scenario_file
