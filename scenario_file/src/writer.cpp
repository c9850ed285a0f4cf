#include "mm/scenario_file/writer.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <system_error>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "mm/number_text.hpp"
#include "mm/scenario_file/loader.hpp"
#include "reader.hpp"

namespace mm::scenario_file {
namespace {

using mm::sim::path;

/// A YAML emitter that writes the format's values: numbers in their shortest exact form, points
/// as `[x, y]`.
class document {
 public:
  document() {
    out_.SetIndent(2);
    out_.SetMapFormat(YAML::Block);
  }

  /// The document written so far.
  std::string yaml() const {
    if (!out_.good()) throw std::logic_error("scenario_text: the YAML emitter failed: " + out_.GetLastError());
    return std::string(out_.c_str()) + "\n";
  }

  void comment(const std::string& line) { out_ << YAML::Comment(line); }
  void begin_map() { out_ << YAML::BeginMap; }
  void begin_flow_map() { out_ << YAML::Flow << YAML::BeginMap; }
  void end_map() { out_ << YAML::EndMap; }
  void begin_list() { out_ << YAML::BeginSeq; }
  void begin_flow_list() { out_ << YAML::Flow << YAML::BeginSeq; }
  void end_list() { out_ << YAML::EndSeq; }
  void key(std::string_view k) { out_ << YAML::Key << std::string(k) << YAML::Value; }

  void number(double value) { out_ << number_text(value); }
  void integer(std::uint64_t value) { out_ << std::to_string(value); }
  void boolean(bool value) { out_ << (value ? "true" : "false"); }
  /// A text, which must be UTF-8 (YAML is Unicode; the emitter would replace other bytes).
  void text(const std::string& value, std::string_view field) {
    if (!detail::is_utf8(value)) {
      throw std::invalid_argument("scenario_text: " + std::string(field) + ": a text that is not UTF-8: expected UTF-8 text");
    }
    out_ << YAML::DoubleQuoted << value;
  }
  void word(std::string_view value) { out_ << std::string(value); }
  void point(vec2 p) {
    begin_flow_list();
    number(p.x);
    number(p.y);
    end_list();
  }
  void points(const std::vector<vec2>& ps) {
    begin_flow_list();
    for (vec2 p : ps) point(p);
    end_list();
  }

  void number(std::string_view k, double value) {
    key(k);
    number(value);
  }
  void integer(std::string_view k, std::uint64_t value) {
    key(k);
    integer(value);
  }
  void boolean(std::string_view k, bool value) {
    key(k);
    boolean(value);
  }

 private:
  YAML::Emitter out_;
};

std::string_view policy_kind_name(mm::forecast_policy_kind kind) {
  switch (kind) {
    case mm::forecast_policy_kind::adjustable: return "adj";
    case mm::forecast_policy_kind::constant: return "const";
    case mm::forecast_policy_kind::robust: return "robust";
  }
  return "adj";
}

/// A path as the steps that rebuild it bit for bit (`mm::sim::steps_of`): its first segment's start
/// pose, then `curve`, `straight_m` or `line_to_m` per segment.
void write_path(document& doc, const path& p) {
  const mm::sim::path_steps built = mm::sim::steps_of(p);
  doc.begin_map();
  doc.key("start");
  doc.begin_flow_map();
  doc.key("position_m");
  doc.point(built.start.position);
  doc.number("heading_rad", built.start.heading);
  doc.end_map();
  doc.key("segments");
  doc.begin_list();
  for (const mm::sim::path_step& step : built.steps) {
    doc.begin_flow_map();
    switch (step.operation) {
      case mm::sim::path_step::kind::curve:
        doc.key("curve");
        doc.begin_flow_map();
        doc.number("length_m", step.length);
        doc.number("curvature_per_m", step.curvature);
        doc.end_map();
        break;
      case mm::sim::path_step::kind::straight: doc.number("straight_m", step.length); break;
      case mm::sim::path_step::kind::line_to:
        doc.key("line_to_m");
        doc.point(step.point);
        break;
    }
    doc.end_map();
  }
  doc.end_list();
  doc.end_map();
}

void write_footprint(document& doc, const mm::rectangle& r) {
  doc.key("footprint");
  doc.begin_flow_map();
  doc.number("length_m", r.length);
  doc.number("width_m", r.width);
  doc.end_map();
}

void write_knots(document& doc, const mm::sim::speed_profile& profile) {
  doc.begin_list();
  for (const mm::sim::speed_knot& k : profile.knots) {
    doc.begin_flow_map();
    doc.number("time_s", k.time);
    doc.number("speed_mps", k.speed);
    doc.end_map();
  }
  doc.end_list();
}

void write_common(document& doc, const std::string& name, std::string_view kind, const path& p, double start_arc_length,
                  double start_time, mm::sim::before_start_behaviour before_start) {
  doc.key("name");
  doc.text(name, std::string(kind) + " name");
  doc.key("kind");
  doc.word(kind);
  doc.key("path");
  write_path(doc, p);
  doc.number("start_arc_length_m", start_arc_length);
  doc.number("start_time_s", start_time);
  doc.key("before_start");
  doc.word(mm::sim::to_string(before_start));
}

void write_car_following(document& doc, const mm::sim::car_following_config& k) {
  doc.number("time_gap_s", k.time_gap);
  doc.number("jam_distance_m", k.jam_distance);
  doc.number("corridor_half_width_m", k.corridor_half_width);
  doc.number("max_heading_difference_rad", k.max_heading_difference);
}

void write_planner(document& doc, const mm::planner_config& c) {
  doc.key("planner");
  doc.begin_map();
  doc.key("policy");
  doc.word(policy_kind_name(c.policy.kind));
  doc.number("forecast_time_s", c.policy.constant_forecast_time);
  doc.number("safety_margin_m", c.safety_margin);
  doc.boolean("urgent_steering", c.urgent_steering);
  doc.number("displacement_horizon_s", c.displacement_horizon);
  doc.number("collision_window_s", c.collision_window);
  doc.number("forecast_step_s", c.forecast_step);
  doc.integer("forecast_count", c.forecast_count);
  doc.number("history_window_s", c.history_window);
  doc.key("resolution");
  doc.begin_flow_map();
  doc.integer("accelerations", c.resolution.accelerations);
  doc.integer("curvatures", c.resolution.curvatures);
  doc.end_map();
  doc.number("max_time_step_s", c.max_time_step);
  doc.key("effort_weights");
  doc.begin_flow_map();
  doc.number("longitudinal", c.effort.longitudinal);
  doc.number("lateral", c.effort.lateral);
  doc.end_map();
  doc.key("assignment_search");
  doc.word(c.assignment_search == mm::assignment_search_kind::exhaustive ? "exhaustive" : "coordinate_ascent");
  doc.integer("max_exhaustive_assignments", c.max_exhaustive_assignments);
  doc.boolean("map_column", c.map_column);
  doc.end_map();
}

void write_planning_vehicle(document& doc, const mm::sim::planning_vehicle& v) {
  doc.begin_map();
  write_common(doc, v.name, "planning_vehicle", v.path, v.start_arc_length, v.start_time, v.before_start);
  doc.number("start_lateral_offset_m", v.start_lateral_offset);
  doc.number("initial_speed_mps", v.initial_speed);
  doc.number("desired_speed_mps", v.desired_speed);
  if (v.desired_speed_profile) {
    doc.key("desired_speed_profile");
    write_knots(doc, *v.desired_speed_profile);
  }
  write_footprint(doc, v.shape);
  doc.key("limits");
  doc.begin_map();
  doc.number("max_acceleration_mps2", v.limits.max_acceleration);
  doc.number("max_deceleration_mps2", v.limits.max_deceleration);
  doc.number("max_lateral_acceleration_mps2", v.limits.max_lateral_acceleration);
  doc.number("min_turning_radius_m", v.limits.min_turning_radius);
  doc.number("speed_cap_mps", v.limits.speed_cap);
  doc.boolean("steering", v.limits.steering);
  doc.end_map();
  write_planner(doc, v.planner);
  doc.key("follower");
  doc.begin_map();
  doc.number("lookahead_time_s", v.follower.lookahead_time);
  doc.number("min_lookahead_m", v.follower.min_lookahead);
  doc.number("speed_gain_per_s", v.follower.speed_gain);
  doc.number("comfortable_deceleration_mps2", v.follower.comfortable_deceleration);
  if (v.follower.curve_lateral_acceleration) {
    doc.number("curve_lateral_acceleration_mps2", *v.follower.curve_lateral_acceleration);
  }
  if (v.follower.car_following) {
    doc.key("car_following");
    doc.begin_map();
    write_car_following(doc, *v.follower.car_following);
    doc.end_map();
  }
  doc.end_map();
  doc.boolean("avoidance", v.avoidance);
  doc.integer("planning_period_steps", v.planning_period);
  doc.end_map();
}

void write_motion(document& doc, const mm::sim::scripted_motion& m) {
  if (m.speed.knots.size() == 1 && m.speed.knots.front().time == 0.0) {
    doc.number("speed_mps", m.speed.knots.front().speed);
  } else {
    doc.key("speed_profile");
    write_knots(doc, m.speed);
  }
  if (m.stop) {
    doc.key("stop");
    doc.begin_flow_map();
    doc.number("arc_length_m", m.stop->arc_length);
    if (m.stop->duration) doc.number("duration_s", *m.stop->duration);
    doc.end_map();
  }
}

void write_scripted_vehicle(document& doc, const mm::sim::scripted_vehicle& v) {
  doc.begin_map();
  write_common(doc, v.name, "scripted_vehicle", v.motion.path, v.motion.start_arc_length, v.motion.start_time,
               v.motion.before_start);
  write_motion(doc, v.motion);
  write_footprint(doc, v.shape);
  if (v.car_following) {
    const mm::sim::scripted_car_following& k = *v.car_following;
    doc.key("car_following");
    doc.begin_map();
    write_car_following(doc, k.following);
    doc.number("max_acceleration_mps2", k.max_acceleration);
    doc.number("comfortable_deceleration_mps2", k.comfortable_deceleration);
    doc.number("max_deceleration_mps2", k.max_deceleration);
    doc.number("speed_gain_per_s", k.speed_gain);
    doc.boolean("follows_scripted", k.follows_scripted);
    doc.end_map();
  }
  doc.end_map();
}

void write_pedestrian(document& doc, const mm::sim::pedestrian& p) {
  doc.begin_map();
  write_common(doc, p.name, "pedestrian", p.motion.path, p.motion.start_arc_length, p.motion.start_time,
               p.motion.before_start);
  write_motion(doc, p.motion);
  doc.number("radius_m", p.radius);
  doc.end_map();
}

void write_static_obstacle(document& doc, const mm::sim::static_obstacle& o) {
  doc.begin_map();
  doc.key("name");
  doc.text(o.name, "static_obstacle name");
  doc.key("kind");
  doc.word("static_obstacle");
  doc.key("vertices_m");
  doc.points(o.vertices);
  doc.end_map();
}

/// The roundabout and roads of a loaded file: drawn, not used by the run.
void write_drawn(document& doc, const loaded_scenario& drawn) {
  if (drawn.roundabout) {
    const roundabout_geometry& g = *drawn.roundabout;
    doc.key("roundabout");
    doc.begin_map();
    doc.key("center_m");
    doc.point(g.ring.center);
    doc.number("radius_m", g.ring.radius);
    doc.number("connection_radius_m", g.ring.connection_radius);
    doc.key("arms");
    doc.begin_map();
    for (const named_arm& arm : g.arms) {
      if (!detail::is_utf8(arm.name)) throw std::invalid_argument("scenario_text: roundabout arm name: a text that is not UTF-8");
      doc.key(arm.name);
      doc.begin_flow_map();
      doc.number("angle_rad", arm.arm.angle);
      doc.number("lane_offset_m", arm.arm.lane_offset);
      doc.number("straight_length_m", arm.arm.straight_length);
      doc.end_map();
    }
    doc.end_map();
    doc.end_map();
  }
  if (!drawn.roads.empty()) {
    doc.key("roads");
    doc.begin_list();
    for (const road& r : drawn.roads) {
      doc.begin_flow_map();
      doc.key("name");
      doc.text(r.name, "road name");
      doc.key("centre_line_m");
      doc.points(r.centre_line);
      doc.number("width_m", r.width);
      doc.end_map();
    }
    doc.end_list();
  }
}

/// Where `read` first differs from `s`, for the message of a write that does not read back.
std::string first_difference(const mm::sim::scenario& s, const mm::sim::scenario& read) {
  const auto agents = [](std::string_view list, const auto& a, const auto& b) -> std::string {
    if (a.size() != b.size()) return std::string(list) + ": " + std::to_string(a.size()) + " agents read back as " + std::to_string(b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!(a[i] == b[i])) return std::string(list) + "[" + std::to_string(i) + "] \"" + a[i].name + "\"";
    }
    return "";
  };
  for (const std::string& where :
       {agents("planning_vehicles", s.planning_vehicles, read.planning_vehicles),
        agents("scripted_vehicles", s.scripted_vehicles, read.scripted_vehicles),
        agents("pedestrians", s.pedestrians, read.pedestrians),
        agents("static_obstacles", s.static_obstacles, read.static_obstacles)}) {
    if (!where.empty()) return where;
  }
  if (!(s.drivable_area == read.drivable_area)) return "drivable_area";
  return "the scenario's own fields";
}

std::string text_of(const mm::sim::scenario& s, const loaded_scenario* drawn) {
  if (auto error = mm::sim::validation_error(s)) throw std::invalid_argument("scenario_text: " + *error);
  for (const mm::sim::planning_vehicle& v : s.planning_vehicles) {
    if (v.planner.record_samples) {
      throw std::invalid_argument("scenario_text: planning vehicle \"" + v.name +
                                  "\": planner.record_samples = true: expected false (a scenario file cannot state it; "
                                  "the drawing tools record the samples they draw)");
    }
  }
  document doc;
  doc.comment("A scenario as the simulator runs it: every field given, SI units, start times resolved");
  doc.begin_map();
  doc.key("format");
  doc.word(format_version);
  doc.key("name");
  doc.text(s.name, "name");
  doc.key("description");
  doc.text(s.description, "description");
  doc.number("duration_s", s.duration);
  doc.number("time_step_s", s.time_step);
  doc.integer("seed", s.seed);
  doc.key("sensing_noise");
  doc.begin_flow_map();
  doc.number("position_sd_m", s.noise.position_sd);
  doc.number("heading_sd_rad", s.noise.heading_sd);
  doc.number("speed_sd_mps", s.noise.speed_sd);
  doc.end_map();
  if (!s.drivable_area.empty()) {
    doc.key("drivable_area");
    doc.begin_map();
    doc.key("polygons_m");
    doc.begin_list();
    for (const std::vector<vec2>& polygon : s.drivable_area.polygons) doc.points(polygon);
    doc.end_list();
    if (!s.drivable_area.open_edges.empty()) {
      doc.key("open_edges");
      doc.begin_flow_list();
      for (const mm::polygon_edge& e : s.drivable_area.open_edges) {
        doc.begin_flow_list();
        doc.integer(e.polygon);
        doc.integer(e.edge);
        doc.end_list();
      }
      doc.end_list();
    }
    doc.end_map();
  }
  if (drawn) write_drawn(doc, *drawn);
  doc.key("agents");
  doc.begin_list();
  for (const mm::sim::planning_vehicle& v : s.planning_vehicles) write_planning_vehicle(doc, v);
  for (const mm::sim::scripted_vehicle& v : s.scripted_vehicles) write_scripted_vehicle(doc, v);
  for (const mm::sim::pedestrian& p : s.pedestrians) write_pedestrian(doc, p);
  for (const mm::sim::static_obstacle& o : s.static_obstacles) write_static_obstacle(doc, o);
  doc.end_list();
  doc.end_map();
  std::string text = doc.yaml();
  // The file must load as `s`: the loader also holds every road user to its sizes and speeds
  // (docs/scenario-format.md), which a scenario built in code may not meet.
  loaded_scenario loaded;
  try {
    loaded = load_text(text, "scenario \"" + s.name + "\" as written");
  } catch (const scenario_error& e) {
    throw std::invalid_argument("scenario_text: the scenario \"" + s.name + "\" is not one a scenario file can state: " +
                                e.field() + (e.problem().rfind("= ", 0) == 0 ? " " : ": ") + e.problem());
  }
  if (!(loaded.scenario == s)) {
    throw std::logic_error("scenario_text: the written scenario does not read back bit for bit: " +
                           first_difference(s, loaded.scenario) + "\n" + text);
  }
  return text;
}

}  // namespace

std::string scenario_text(const mm::sim::scenario& s) { return text_of(s, nullptr); }

std::string scenario_text(const loaded_scenario& loaded) { return text_of(loaded.scenario, &loaded); }

namespace {

void write_text(const std::string& text, const std::filesystem::path& file) {
  const auto fail = [&] {
    throw std::filesystem::filesystem_error("cannot write the scenario file", file,
                                            std::error_code(errno, std::generic_category()));
  };
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) fail();
  out << text;
  out.close();
  if (!out) fail();
}

}  // namespace

void write_file(const mm::sim::scenario& s, const std::filesystem::path& file) { write_text(scenario_text(s), file); }

void write_file(const loaded_scenario& loaded, const std::filesystem::path& file) {
  write_text(scenario_text(loaded), file);
}

}  // namespace mm::scenario_file
