#include "mm/cli/commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <variant>

#include "output_files.hpp"
#include "mm/cli/commonroad_export.hpp"
#include "mm/commonroad/writer.hpp"
#include "mm/forecast.hpp"
#include "mm/maneuver.hpp"
#include "mm/sim/roundabout.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::cli {
namespace {

using json = nlohmann::ordered_json;
using output::footprint_json;
using output::point;
using output::points;
using output::rounded;
using output::write_text;

json optional_number(const std::optional<double>& value, int decimals = 6) {
  return value && std::isfinite(*value) ? json(rounded(*value, decimals)) : json(nullptr);
}

/// The path as a polyline: every segment's start, arcs every ≤ 0.5 m, and the end.
json sampled(const mm::sim::path& p) {
  json points = json::array();
  if (p.empty()) return points;
  constexpr double spacing = 0.5;       // [m]
  constexpr std::size_t max_points = 20000;
  const double length = p.length();
  for (const mm::sim::path_segment& seg : p.segments()) {
    const std::size_t pieces =
        seg.curvature == 0.0 ? 1 : std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(seg.length / spacing)), 1, 2000);
    for (std::size_t k = 0; k < pieces && points.size() < max_points; ++k) {
      points.push_back(point(p.at(seg.start_arc_length + seg.length * static_cast<double>(k) / static_cast<double>(pieces)).position));
    }
  }
  points.push_back(point(p.at(length).position));
  return points;
}

json scene_json(const scenario_file::loaded_scenario& loaded) {
  const mm::sim::scenario& s = loaded.scenario;
  json agents = json::array();
  for (const mm::sim::planning_vehicle& v : s.planning_vehicles) {
    agents.push_back({{"name", v.name},
                      {"kind", "planning_vehicle"},
                      {"footprint", footprint_json(v.shape)},
                      {"start_time_s", rounded(v.start_time)},
                      {"start_arc_length_m", rounded(v.start_arc_length, 4)},
                      {"path_m", sampled(v.path)}});
  }
  const auto motion = [&](const std::string& name, const char* kind, const mm::footprint& shape,
                          const mm::sim::scripted_motion& m) {
    json stop = nullptr;
    if (m.stop) stop = point(m.path.at(m.stop->arc_length).position);
    agents.push_back({{"name", name},
                      {"kind", kind},
                      {"footprint", footprint_json(shape)},
                      {"start_time_s", rounded(m.start_time)},
                      {"start_arc_length_m", rounded(m.start_arc_length, 4)},
                      {"path_m", sampled(m.path)},
                      {"stop_m", stop}});
  };
  for (const mm::sim::scripted_vehicle& v : s.scripted_vehicles) motion(v.name, "scripted_vehicle", v.shape, v.motion);
  for (const mm::sim::pedestrian& p : s.pedestrians) motion(p.name, "pedestrian", mm::disc{p.radius}, p.motion);
  for (const mm::sim::static_obstacle& o : s.static_obstacles) {
    agents.push_back({{"name", o.name}, {"kind", "static_obstacle"}, {"vertices_m", points(o.vertices)}});
  }

  json ring = nullptr;
  if (loaded.roundabout) {
    const mm::sim::roundabout& r = loaded.roundabout->ring;
    json arms = json::array();
    for (const scenario_file::named_arm& arm : loaded.roundabout->arms) {
      // The lanes of the arm: in (straight and connecting arc) and out, without the ring itself.
      const mm::sim::path in = mm::sim::roundabout_entry_route(r, arm.arm, 1e-9);
      const mm::sim::path out = mm::sim::roundabout_exit_route(r, mm::sim::diverge_angle(r, arm.arm) - 1e-9, arm.arm);
      arms.push_back({{"name", arm.name},
                      {"angle_deg", rounded(arm.arm.angle * 180.0 / std::numbers::pi)},
                      {"lane_offset_m", rounded(arm.arm.lane_offset, 4)},
                      {"straight_length_m", rounded(arm.arm.straight_length, 4)},
                      {"entry_lane_m", sampled(in)},
                      {"exit_lane_m", sampled(out)}});
    }
    ring = {{"center_m", point(r.center)},
            {"radius_m", rounded(r.radius, 4)},
            {"connection_radius_m", rounded(r.connection_radius, 4)},
            {"arms", arms}};
  }
  json roads = json::array();
  for (const scenario_file::road& road : loaded.roads) {
    json line = json::array();
    for (vec2 p : road.centre_line) line.push_back(point(p));
    roads.push_back({{"name", road.name}, {"centre_line_m", line}, {"width_m", rounded(road.width, 4)}});
  }
  return {{"format", "maneuvermap-scene/1"},
          {"scenario", s.name},
          {"description", s.description},
          {"duration_s", rounded(s.duration)},
          {"time_step_s", rounded(s.time_step)},
          {"agents", agents},
          {"roundabout", ring},
          {"roads", roads},
          {"drivable_area", output::drivable_area_json(
                                s.drivable_area.empty() ? nullptr
                                                        : std::make_shared<const mm::drivable_area>(s.drivable_area))}};
}

json metrics_json(const mm::sim::run_metrics& m, const std::string& policy, bool with_cpu) {
  return {{"agent", m.agent},
          {"policy", policy},
          {"crash", m.crash},
          {"crash_time_s", optional_number(m.crash_time_s)},
          {"crash_with", m.crash ? json(m.crash_with) : json(nullptr)},
          {"min_dist_m", optional_number(m.min_dist_m)},
          {"min_dist_time_s", optional_number(m.min_dist_time_s)},
          {"closest_agent", m.closest_agent.empty() ? json(nullptr) : json(m.closest_agent)},
          {"ttc_at_min_s", optional_number(m.ttc_at_min_s)},
          {"speed_kmh", optional_number(m.speed_kmh)},
          {"bypass", std::string(mm::sim::to_string(m.bypass))},
          {"lateral_offset_at_min_m", rounded(m.lateral_offset_at_min_m)},
          {"max_lateral_offset_m", rounded(m.max_lateral_offset_m)},
          {"min_speed_kmh", rounded(m.min_speed_kmh)},
          {"max_speed_kmh", rounded(m.max_speed_kmh)},
          {"time_in_brake_s", rounded(m.time_in_brake_s)},
          {"time_in_accel_s", rounded(m.time_in_accel_s)},
          {"planning_steps", m.planning_steps},
          {"cpu_median_us", with_cpu ? json(rounded(m.cpu_median_us, 3)) : json(nullptr)},
          {"cpu_p99_us", with_cpu ? json(rounded(m.cpu_p99_us, 3)) : json(nullptr)}};
}

/// A CSV file filled through a buffer.
class csv_file {
 public:
  csv_file(const std::filesystem::path& file, std::string_view header) : path_(file), out_(file, std::ios::binary) {
    if (!out_) throw std::runtime_error("cannot write " + file.string());
    fmt::format_to(std::back_inserter(buffer_), "{}\n", header);
  }
  fmt::memory_buffer& buffer() { return buffer_; }
  void flush(bool force = false) {
    if (!force && buffer_.size() < (1U << 20)) return;
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!out_) throw std::runtime_error("cannot write " + path_.string());
  }
  void close() {
    flush(true);
    out_.close();
    if (!out_) throw std::runtime_error("cannot write " + path_.string());
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  fmt::memory_buffer buffer_;
};

/// `fixed(value, decimals)` (decimals 0 to 17) appended to `out` without a string in between:
/// std::to_chars, correctly rounded as fmt's "{:.6f}" is, so the same characters.
void append_fixed(fmt::memory_buffer& out, double value, int decimals = 6) {
  if (!std::isfinite(value)) return;
  // The longest fixed text of a finite double: 309 digits before the point, the point, the decimals.
  std::array<char, 330> text{};
  const std::to_chars_result end = std::to_chars(text.data(), text.data() + text.size(), value,
                                                 std::chars_format::fixed, std::clamp(decimals, 0, 17));
  const char* begin = text.data();
  const char* last = end.ptr;
  // "-0.000" is written "0.000".
  if (*begin == '-' && std::all_of(begin + 1, last, [](char c) { return c == '0' || c == '.'; })) ++begin;
  out.append(begin, last);
}

}  // namespace

std::string fixed(double value, int decimals) {
  fmt::memory_buffer out;
  append_fixed(out, value, decimals);
  return fmt::to_string(out);
}

std::string scenario_policy(const mm::sim::scenario& s) {
  if (s.planning_vehicles.empty()) return "none";
  const std::string first = scenario_file::policy_name(s.planning_vehicles.front().planner.policy);
  for (const mm::sim::planning_vehicle& v : s.planning_vehicles) {
    if (scenario_file::policy_name(v.planner.policy) != first) return "mixed";
  }
  return first;
}

run_outcome run_scenario(const scenario_file::loaded_scenario& loaded, const run_settings& settings) {
  const mm::sim::scenario& s = loaded.scenario;
  // First the simulation, which refuses an invalid scenario: then nothing has been written.
  mm::sim::simulation sim(s, {settings.measure_cpu_time, settings.jobs});
  std::optional<commonroad_recording> recording;
  if (!settings.commonroad_file.empty()) recording.emplace(loaded, settings.commonroad_step);
  std::filesystem::create_directories(settings.out_dir);
  const auto file = [&](const char* name) { return settings.out_dir / name; };
  csv_file trajectories(file("trajectories.csv"), "t,agent,x,y,heading,speed,accel,curvature");
  csv_file map(file("map.csv"), "t,agent,tau,mi_brake,mi_accel,excluded");
  csv_file decisions(file("decisions.csv"), "t,agent,tau_bar,family,mode,ttc,cpu_us,robust");

  std::size_t shown_step = 0;
  mm::sim::run(sim, [&](const mm::sim::simulation& now) {
    if (recording) recording->record(now);
    fmt::memory_buffer t;
    append_fixed(t, now.time());
    const std::string_view time(t.data(), t.size());
    // Fields appended one by one: a row's numbers go straight into the file's buffer.
    const auto field = [](fmt::memory_buffer& row, std::string_view text) {
      row.append(text);
      row.push_back(',');
    };
    const auto number = [](fmt::memory_buffer& row, double value, char after) {
      append_fixed(row, value);
      row.push_back(after);
    };
    for (mm::sim::agent_id id = 0; id < now.agent_count(); ++id) {
      const mm::sim::agent_state& a = now.state(id);
      if (!a.present()) continue;
      fmt::memory_buffer& row = trajectories.buffer();
      field(row, time);
      field(row, now.info(id).name);
      number(row, a.pose.position.x, ',');
      number(row, a.pose.position.y, ',');
      number(row, a.pose.heading, ',');
      number(row, a.speed, ',');
      number(row, a.acceleration, ',');
      number(row, a.curvature, '\n');
    }
    for (mm::sim::agent_id id = 0; id < now.planning_vehicle_count(); ++id) {
      if (!now.planned_now(id)) continue;
      const mm::sim::plan_record& p = *now.last_plan(id);
      const mm::plan_result& r = p.result;
      const std::string& name = now.info(id).name;
      // A vehicle whose planner computes no map column (`planner_config::map_column` false) has no rows.
      for (std::size_t i = 0; i < r.mi_brake.size(); ++i) {
        fmt::memory_buffer& row = map.buffer();
        field(row, time);
        field(row, name);
        number(row, r.forecast_times[i], ',');
        number(row, r.mi_brake[i], ',');
        number(row, r.mi_accelerate[i], ',');
        row.append(std::string_view(r.excluded[i] ? "1\n" : "0\n"));
      }
      fmt::memory_buffer& row = decisions.buffer();
      field(row, time);
      field(row, name);
      number(row, r.forecast_time, ',');
      field(row, mm::to_string(r.selected_family));
      field(row, mm::to_string(r.mode));
      number(row, r.time_to_collision, ',');
      if (settings.measure_cpu_time) append_fixed(row, p.cpu_time_us, 3);
      row.append(std::string_view(r.robust ? ",1\n" : ",0\n"));
    }
    trajectories.flush();
    map.flush();
    decisions.flush();
    if (settings.progress != nullptr && (now.step_index() - shown_step >= 10 || now.ended())) {
      shown_step = now.step_index();
      *settings.progress << fmt::format("\r{}: t = {:.2f} / {:.2f} s", s.name, now.time(), s.duration) << std::flush;
    }
  });
  if (settings.progress != nullptr) *settings.progress << "\r\033[K" << std::flush;
  trajectories.close();
  map.close();
  decisions.close();

  run_outcome outcome;
  outcome.metrics = sim.all_metrics();
  outcome.end_time = sim.time();

  json parameters = json::object();
  for (const scenario_file::parameter& p : loaded.parameters) parameters[p.name] = p.value;
  json meetings = json::array();
  for (const scenario_file::meeting_report& m : loaded.meetings) {
    meetings.push_back({{"agents", json::array({m.first, m.second})},
                        {"distances_m", json::array({rounded(m.first_distance), rounded(m.second_distance)})},
                        {"travel_times_s", json::array({rounded(m.first_travel), rounded(m.second_travel)})},
                        {"lag_s", rounded(m.lag)},
                        {"start_times_s", json::array({rounded(m.first_start), rounded(m.second_start)})}});
  }
  json crashes = json::array();
  for (const mm::sim::crash_event& c : sim.crashes()) {
    crashes.push_back({{"time_s", rounded(c.time)}, {"agents", json::array({sim.info(c.first).name, sim.info(c.second).name})}});
  }
  json vehicles = json::array();
  for (std::size_t i = 0; i < outcome.metrics.size(); ++i) {
    vehicles.push_back(metrics_json(outcome.metrics[i], scenario_file::policy_name(s.planning_vehicles[i].planner.policy),
                                    settings.measure_cpu_time));
  }
  const json summary = {{"format", "maneuvermap-summary/1"},
                        {"scenario", s.name},
                        {"policy", scenario_policy(s)},
                        {"seed", s.seed},
                        {"parameters", parameters},
                        {"duration_s", rounded(s.duration)},
                        {"time_step_s", rounded(s.time_step)},
                        {"end_time_s", rounded(outcome.end_time)},
                        {"cpu_timing", settings.measure_cpu_time},
                        {"meetings", meetings},
                        {"crashes", crashes},
                        {"vehicles", vehicles}};
  write_text(file("summary.json"), summary.dump(2) + "\n");
  write_text(file("scene.json"), scene_json(loaded).dump() + "\n");  // compact: mostly long point lists
  for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
    outcome.files.push_back(file(name).string());
  }
  if (recording) {
    mm::commonroad::write_scenario(recording->scenario(), settings.commonroad_file);
    outcome.files.push_back(settings.commonroad_file.string());
  }
  return outcome;
}

std::string metrics_table(const std::vector<mm::sim::run_metrics>& metrics, bool with_cpu) {
  std::vector<std::vector<std::string>> rows{{"agent", "crash", "min_dist_m", "ttc_at_min_s", "speed_kmh", "bypass",
                                              "min_speed_kmh", "max_speed_kmh", "time_in_brake_s", "time_in_accel_s"}};
  if (with_cpu) {
    rows[0].push_back("cpu_median_us");
    rows[0].push_back("cpu_p99_us");
  }
  const auto opt = [](const std::optional<double>& v, int decimals) { return v ? fixed(*v, decimals) : std::string("-"); };
  for (const mm::sim::run_metrics& m : metrics) {
    std::vector<std::string> row{m.agent,
                                 m.crash ? "yes" : "no",
                                 opt(m.min_dist_m, 3),
                                 opt(m.ttc_at_min_s, 3),
                                 opt(m.speed_kmh, 1),
                                 std::string(mm::sim::to_string(m.bypass)),
                                 fixed(m.min_speed_kmh, 1),
                                 fixed(m.max_speed_kmh, 1),
                                 fixed(m.time_in_brake_s, 2),
                                 fixed(m.time_in_accel_s, 2)};
    if (with_cpu) {
      // A step with no obstacle within reach plans in well under a microsecond: one decimal.
      row.push_back(fixed(m.cpu_median_us, 1));
      row.push_back(fixed(m.cpu_p99_us, 1));
    }
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> widths(rows[0].size(), 0);
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  std::string out;
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      // Names and words left-aligned, numbers right-aligned.
      const bool left = c == 0 || c == 1 || c == 5;
      out += c == 0 ? "" : "  ";
      out += left ? fmt::format("{:<{}}", row[c], widths[c]) : fmt::format("{:>{}}", row[c], widths[c]);
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    out += "\n";
  }
  return out;
}

namespace {

/// A number as the user gave it, short: 2, 0.3, 1e+300, nan.
std::string as_given(double value) { return fmt::format("{:g}", value); }

}  // namespace

snapshot take_snapshot(const scenario_file::loaded_scenario& loaded, const std::string& agent, double time,
                       std::optional<double> tau) {
  const mm::sim::scenario& s = loaded.scenario;
  if (!std::isfinite(time) || time < 0.0 || time > s.duration + 1e-9) {
    throw input_error("--time " + as_given(time) + ": expected a time from 0 to the duration " + fixed(s.duration, 3) + " s");
  }
  mm::sim::simulation sim(s);
  const std::optional<mm::sim::agent_id> id = sim.find(agent);
  if (!id || *id >= sim.planning_vehicle_count()) {
    std::string names;
    for (const mm::sim::planning_vehicle& v : s.planning_vehicles) names += (names.empty() ? "" : ", ") + v.name;
    throw input_error("--agent " + agent + ": " + (id ? "not a planning vehicle" : "no such agent") +
                      " (planning vehicles: " + (names.empty() ? "none" : names) + ")");
  }
  const double tolerance = 1e-9 * std::max(1.0, time);
  while (!sim.ended() && sim.time() < time - tolerance) sim.step();
  if (sim.time() < time - tolerance) {
    throw input_error("--time " + as_given(time) + ": the run ended at t = " + fixed(sim.time(), 3) +
                      " s (a crash, or every planning vehicle finished its path)");
  }
  if (sim.state(*id).status != mm::sim::agent_status::active) {
    throw input_error("--agent " + agent + ": not driving at t = " + fixed(sim.time(), 3) + " s (status " +
                      std::string(mm::sim::to_string(sim.state(*id).status)) + ")");
  }
  snapshot shot;
  shot.agent = agent;
  shot.time = sim.time();
  shot.input = *sim.planning_input(*id);
  shot.input.config.record_samples = true;
  shot.result = mm::plan(shot.input);
  if (!shot.result.ok() || !shot.result.samples) throw std::runtime_error("re-planning failed: " + shot.result.error);
  for (const mm::obstacle_track& track : shot.input.obstacles) shot.obstacle_names.push_back(sim.info(track.id).name);
  const std::vector<double>& taus = shot.result.forecast_times;
  std::vector<std::size_t> selected;
  for (std::size_t i = 0; i < taus.size(); ++i) {
    if (!tau || std::abs(taus[i] - *tau) <= 1e-6) selected.push_back(i);
  }
  if (tau && selected.empty()) {
    throw input_error("--tau " + as_given(*tau) + ": not on the forecast grid (0 to " + fixed(taus.back(), 3) +
                      " s in steps of " + fixed(shot.input.config.forecast_step, 3) + " s)");
  }
  const mm::sample_snapshot& samples = *shot.result.samples;
  for (std::size_t i : selected) {
    for (std::size_t m = 0; m < samples.maneuvers.size(); ++m) {
      shot.rows.push_back({taus[i], samples.families[m], samples.maneuvers[m], samples.end_points[m],
                           samples.area_weights[m], samples.safe_by_forecast[i][m] != 0,
                           samples.safe_selected[m] != 0});
    }
  }
  return shot;
}

void write_snapshot_csv(std::ostream& out, const snapshot& shot) {
  fmt::memory_buffer buffer;
  fmt::format_to(std::back_inserter(buffer), "tau,family,accel,curvature,end_x,end_y,area_weight,safe,selected\n");
  for (const snapshot_row& r : shot.rows) {
    fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{},{}\n", fixed(r.forecast_time),
                   mm::to_string(r.fam), fixed(r.u.acceleration), fixed(r.u.curvature), fixed(r.end_point.x),
                   fixed(r.end_point.y), fixed(r.area_weight), r.safe ? 1 : 0, r.selected ? 1 : 0);
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

std::filesystem::path snapshot_json_path(const std::filesystem::path& csv) {
  std::filesystem::path json_file = csv;
  if (json_file.extension() == ".json") return json_file += ".json";  // never the CSV itself
  return json_file.replace_extension(".json");
}

void write_snapshot_json(std::ostream& out, const snapshot& shot, const scenario_file::loaded_scenario& loaded) {
  const mm::plan_input& in = shot.input;
  const mm::plan_result& r = shot.result;
  const double horizon = in.config.displacement_horizon;
  const auto displacement = [&](const mm::maneuver& u) {
    const mm::pose end = mm::maneuver_pose(in.ego.pose, in.ego.speed, u, horizon, horizon, in.ego.limits.speed_cap);
    return json{{"accel_mps2", rounded(u.acceleration)}, {"curvature_per_m", rounded(u.curvature)}, {"end_m", point(end.position)}};
  };
  const auto index_of = [&](double tau) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
      if (std::abs(r.forecast_times[i] - tau) < std::abs(r.forecast_times[best] - tau)) best = i;
    }
    return best;
  };
  json obstacles = json::array();
  for (std::size_t k = 0; k < in.obstacles.size() && k < r.obstacles.size(); ++k) {
    const mm::obstacle_assessment& a = r.obstacles[k];
    const double tau = a.forecast_index < r.forecast_times.size() ? r.forecast_times[a.forecast_index] : r.forecast_time;
    json forecast = json::array();
    constexpr int samples = 30;
    for (int i = 0; i <= samples; ++i) {
      const double t = in.config.collision_window * i / samples;
      forecast.push_back(point(mm::forecast_pose(a.motion, tau, t).position));
    }
    obstacles.push_back({{"name", k < shot.obstacle_names.size() ? shot.obstacle_names[k] : std::to_string(a.id)},
                         {"footprint", footprint_json(in.obstacles[k].shape)},
                         {"relevant", a.relevant},
                         {"position_m", point(a.motion.pose.position)},
                         {"heading_rad", rounded(a.motion.pose.heading)},
                         {"speed_mps", rounded(a.motion.speed)},
                         {"yaw_rate_per_s", rounded(a.motion.yaw_rate)},
                         {"ttc_s", optional_number(a.time_to_collision)},
                         {"tau_s", rounded(tau)},
                         {"forecast_m", forecast}});
  }
  const std::size_t bar = index_of(r.forecast_time);
  const json doc = {
      {"format", "maneuvermap-snapshot/1"},
      {"scenario", loaded.scenario.name},
      {"policy", scenario_file::policy_name(in.config.policy)},
      {"seed", loaded.scenario.seed},
      {"agent", shot.agent},
      {"time_s", rounded(shot.time)},
      {"ego", {{"position_m", point(in.ego.pose.position)},
               {"heading_rad", rounded(in.ego.pose.heading)},
               {"speed_mps", rounded(in.ego.speed)},
               {"footprint", footprint_json(in.ego.shape)}}},
      {"displacement_horizon_s", rounded(horizon)},
      {"collision_window_s", rounded(in.config.collision_window)},
      {"tau_bar_s", rounded(r.forecast_time)},
      {"family", std::string(mm::to_string(r.selected_family))},
      {"mode", std::string(mm::to_string(r.mode))},
      {"ttc_s", optional_number(r.time_to_collision)},
      {"mi_brake_at_tau_bar", r.mi_brake.empty() ? json(nullptr) : json(rounded(r.mi_brake[bar]))},
      {"mi_accel_at_tau_bar", r.mi_accelerate.empty() ? json(nullptr) : json(rounded(r.mi_accelerate[bar]))},
      {"mi_brake_selected", rounded(r.mi_brake_selected)},
      {"mi_accel_selected", rounded(r.mi_accelerate_selected)},
      {"robust", r.robust},
      {"nominal", displacement(in.nominal)},
      {"chosen", displacement(r.command)},
      {"obstacles", obstacles}};
  out << doc.dump(2) << "\n";
}

}  // namespace mm::cli
