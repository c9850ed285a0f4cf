#include "mm/cli/measure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <ostream>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>
#include <vector>

#include "output_files.hpp"
#include "mm/cli/commands.hpp"
#include "mm/drivable_area.hpp"
#include "mm/scenario_file/loader.hpp"

namespace mm::cli {
namespace {

using output::json;
using output::point;
using output::rounded;

namespace cr = mm::commonroad;

std::string name_of(std::uint32_t id) { return std::to_string(id); }

/// The recording's steps: from the earliest to the latest state of any obstacle.
std::pair<std::int64_t, std::int64_t> step_range(const cr::scenario& s) {
  std::int64_t first = std::numeric_limits<std::int64_t>::max();
  std::int64_t last = std::numeric_limits<std::int64_t>::min();
  for (const cr::obstacle& o : s.obstacles) {
    if (o.states.empty()) continue;
    first = std::min(first, o.states.front().step);
    last = std::max(last, o.states.back().step);
  }
  if (first > last) return {0, 0};
  return {first, last};
}

json scene_json(const cr::scenario& s, const std::string& name, const std::vector<std::uint32_t>& measured,
                const std::shared_ptr<const drivable_area>& area) {
  const auto [first, last] = step_range(s);
  json agents = json::array();
  for (const cr::obstacle& o : s.obstacles) {
    if (o.states.empty()) continue;
    if (o.role == cr::obstacle_role::static_obstacle) {
      const cr::state& x = o.states.front();
      agents.push_back({{"name", name_of(o.id)},
                        {"kind", "static_obstacle"},
                        {"vertices_m", output::points(cr::world_polygon(o.shape, x))}});
      continue;
    }
    const bool is_measured = std::find(measured.begin(), measured.end(), o.id) != measured.end();
    json path = json::array();
    for (const cr::state& x : o.states) path.push_back(point(x.position));
    agents.push_back({{"name", name_of(o.id)},
                      {"kind", is_measured ? "planning_vehicle" : (o.type == "pedestrian" ? "pedestrian" : "scripted_vehicle")},
                      {"type", o.type},
                      {"footprint", output::footprint_json(o.shape)},
                      {"start_time_s", rounded(static_cast<double>(o.states.front().step) * s.time_step)},
                      {"path_m", path}});
  }
  json lanelets = json::array();
  for (const cr::lanelet& l : s.lanelets) {
    lanelets.push_back({{"id", l.id}, {"left_m", output::points(l.left_bound)}, {"right_m", output::points(l.right_bound)}});
  }
  return {{"format", "maneuvermap-scene/1"},
          {"scenario", name},
          {"description", "CommonRoad " + s.version + " recording " + s.benchmark_id},
          {"duration_s", rounded(static_cast<double>(last - first) * s.time_step)},
          {"time_step_s", rounded(s.time_step)},
          {"agents", agents},
          {"roundabout", nullptr},
          {"roads", json::array()},
          {"lanelets", lanelets},
          {"drivable_area", output::drivable_area_json(area)}};
}

/// Per measured road user: the step of least room and how often the recorded maneuver was unsafe.
struct measurement_summary {
  std::size_t steps = 0;
  double least_room = 1.0;
  double least_room_time = 0.0;
  std::size_t unsafe_steps = 0;  ///< planning mode not nominal: what it did was not safe (spec §8)
  double earliest_ttc = std::numeric_limits<double>::infinity();
  double earliest_ttc_time = 0.0;
};

measurement_summary summarize(const cr::measurement& m) {
  measurement_summary sum;
  sum.steps = m.steps.size();
  for (const cr::measured_step& step : m.steps) {
    const double room = cr::room(step.result);
    if (&step == &m.steps.front() || room < sum.least_room) {
      sum.least_room = room;
      sum.least_room_time = step.time;
    }
    if (step.result.mode != mm::planning_mode::nominal) ++sum.unsafe_steps;
    if (step.result.time_to_collision < sum.earliest_ttc) {
      sum.earliest_ttc = step.result.time_to_collision;
      sum.earliest_ttc_time = step.time;
    }
  }
  return sum;
}

json summary_json(const cr::scenario& s, const std::string& name, const measure_settings& settings,
                  const measure_outcome& outcome) {
  const auto [first, last] = step_range(s);
  json vehicles = json::array();
  for (const cr::measurement& m : outcome.measurements) {
    const measurement_summary sum = summarize(m);
    const auto on_road = std::count_if(m.steps.begin(), m.steps.end(),
                                       [](const cr::measured_step& step) { return step.result.on_drivable_area; });
    vehicles.push_back({{"agent", name_of(m.agent)},
                        {"steps", sum.steps},
                        {"steps_on_drivable_area", on_road},
                        {"least_room", rounded(sum.least_room)},
                        {"least_room_time_s", rounded(sum.least_room_time)},
                        {"unsafe_steps", sum.unsafe_steps},
                        {"earliest_ttc_s", std::isfinite(sum.earliest_ttc) ? json(rounded(sum.earliest_ttc)) : json(nullptr)},
                        {"earliest_ttc_time_s", std::isfinite(sum.earliest_ttc) ? json(rounded(sum.earliest_ttc_time)) : json(nullptr)}});
  }
  return {{"format", "maneuvermap-measurement/1"},
          {"scenario", name},
          {"commonroad_version", s.version},
          {"benchmark_id", s.benchmark_id},
          {"policy", scenario_file::policy_name(settings.policy)},
          {"drivable_area", settings.on_lanelets ? json("lanelets") : json(nullptr)},
          {"seed", 0},
          {"parameters", json::object()},
          {"duration_s", rounded(static_cast<double>(last - first) * s.time_step)},
          {"time_step_s", rounded(s.time_step)},
          {"end_time_s", rounded(static_cast<double>(last) * s.time_step)},
          {"cpu_timing", false},
          {"meetings", json::array()},
          {"crashes", json::array()},
          {"vehicles", vehicles}};
}

void append_number(std::string& row, double value, char after) {
  row += fixed(value);
  row += after;
}

/// trajectories.csv: every obstacle at every step it is recorded (static ones at every step), in
/// file order within a step; accel and curvature are `commonroad::recorded_maneuver`.
std::string trajectories_csv(const cr::scenario& s) {
  const auto [first, last] = step_range(s);
  std::string text = "t,agent,x,y,heading,speed,accel,curvature\n";
  for (std::int64_t k = first; k <= last; ++k) {
    const std::string t = fixed(static_cast<double>(k) * s.time_step);
    for (const cr::obstacle& o : s.obstacles) {
      if (o.states.empty()) continue;
      const bool is_static = o.role == cr::obstacle_role::static_obstacle;
      const std::int64_t index = is_static ? 0 : k - o.states.front().step;
      if (index < 0 || index >= static_cast<std::int64_t>(o.states.size())) continue;
      const auto i = static_cast<std::size_t>(index);
      const cr::state& x = o.states[i];
      const mm::maneuver u = is_static ? mm::maneuver{} : cr::recorded_maneuver(o, i, s.time_step);
      text += t + ',' + name_of(o.id) + ',';
      append_number(text, x.position.x, ',');
      append_number(text, x.position.y, ',');
      append_number(text, wrap_angle(x.orientation), ',');
      append_number(text, is_static ? 0.0 : std::max(x.velocity, 0.0), ',');
      append_number(text, u.acceleration, ',');
      append_number(text, u.curvature, '\n');
    }
  }
  return text;
}

}  // namespace

std::vector<std::uint32_t> road_users_to_measure(const cr::scenario& s, const measure_settings& settings) {
  if (settings.every_road_user) {
    std::vector<std::uint32_t> all = cr::measurable_road_users(s);
    if (all.empty()) throw input_error("--agent all: the file has no road user that can be measured (no vehicle moves in it)");
    return all;
  }
  if (!settings.agents.empty()) return settings.agents;
  if (const auto ego = planning_problem_ego(s)) return {*ego};
  throw input_error("no obstacle of the file replays the ego of its planning problem; choose the road user to measure "
                    "with --agent ID (or --agent all); the road users that can be measured are: " +
                    cr::measurable_road_users_text(s));
}

std::optional<std::uint32_t> planning_problem_ego(const cr::scenario& s) {
  for (const cr::planning_problem& p : s.planning_problems) {
    if (const auto ego = cr::recorded_ego(s, p)) return ego;
  }
  return std::nullopt;
}

measure_outcome measure_recording(const cr::scenario& s, const std::string& name, const measure_settings& settings) {
  const std::vector<std::uint32_t> agents = road_users_to_measure(s, settings);
  measure_outcome outcome;
  outcome.measurements.resize(agents.size());
  // Road users are independent: `jobs` threads take them in turn, each result in its place. The
  // first error (in road-user order) is rethrown once all threads are done.
  std::vector<std::exception_ptr> errors(agents.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;
  std::shared_ptr<const drivable_area> area;
  if (settings.on_lanelets) {
    try {
      area = std::make_shared<const drivable_area>(cr::lanelet_polygons(s));
    } catch (const std::invalid_argument& e) {
      throw input_error(std::string("--on-lanelets: ") + e.what());
    }
  }
  const auto work = [&] {
    cr::measure_options options;
    options.config.policy = settings.policy;
    options.drivable_area = area;
    for (std::size_t i = next++; i < agents.size(); i = next++) {
      options.agent = agents[i];
      try {
        outcome.measurements[i] = cr::measure(s, options);
      } catch (...) {
        errors[i] = std::current_exception();
      }
      if (settings.progress != nullptr) {
        const std::lock_guard lock(progress_mutex);
        *settings.progress << fmt::format("\r{}: {} / {} road users measured", name, ++done, agents.size()) << std::flush;
      }
    }
  };
  {
    std::vector<std::jthread> threads;
    for (std::size_t j = 1; j < std::min(settings.jobs, agents.size()); ++j) threads.emplace_back(work);
    work();
  }
  if (settings.progress != nullptr) *settings.progress << "\r\033[K" << std::flush;
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }

  // map.csv and decisions.csv by time, then road user, as `maneuvermap run` writes them.
  struct row_key {
    double time;
    std::size_t measurement;
    std::size_t step;
  };
  std::vector<row_key> keys;
  for (std::size_t m = 0; m < outcome.measurements.size(); ++m) {
    for (std::size_t k = 0; k < outcome.measurements[m].steps.size(); ++k) {
      keys.push_back({outcome.measurements[m].steps[k].time, m, k});
    }
  }
  std::stable_sort(keys.begin(), keys.end(), [](const row_key& a, const row_key& b) { return a.time < b.time; });
  std::string map = "t,agent,tau,mi_brake,mi_accel,excluded\n";
  std::string decisions = "t,agent,tau_bar,family,mode,ttc,cpu_us,robust\n";
  std::string rooms = "t,agent,speed,room,mode,ttc\n";
  for (const row_key& key : keys) {
    const cr::measured_step& step = outcome.measurements[key.measurement].steps[key.step];
    const plan_result& r = step.result;
    const std::string prefix = fixed(step.time) + ',' + name_of(outcome.measurements[key.measurement].agent) + ',';
    for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
      map += prefix;
      append_number(map, r.forecast_times[i], ',');
      append_number(map, r.mi_brake[i], ',');
      append_number(map, r.mi_accelerate[i], ',');
      map += r.excluded[i] ? "1\n" : "0\n";
    }
    decisions += prefix;
    append_number(decisions, r.forecast_time, ',');
    decisions += std::string(mm::to_string(r.selected_family)) + ',' + std::string(mm::to_string(r.mode)) + ',';
    decisions += fixed(r.time_to_collision) + (r.robust ? ",,1\n" : ",,0\n");
    rooms += prefix;
    append_number(rooms, step.ego.speed, ',');
    append_number(rooms, cr::room(r), ',');
    rooms += std::string(mm::to_string(r.mode)) + ',' + fixed(r.time_to_collision) + '\n';
  }

  std::filesystem::create_directories(settings.out_dir);
  const auto write = [&](const char* file, const std::string& text) {
    output::write_text(settings.out_dir / file, text);
    outcome.files.push_back((settings.out_dir / file).string());
  };
  write("trajectories.csv", trajectories_csv(s));
  write("map.csv", map);
  write("decisions.csv", decisions);
  write("summary.json", summary_json(s, name, settings, outcome).dump(2) + "\n");
  write("scene.json", scene_json(s, name, agents, area).dump() + "\n");
  write("rooms.csv", rooms);
  return outcome;
}

std::string measurements_csv(std::span<const measured_file> files) {
  std::string text = "file,agent,steps,least_room,least_room_time_s,unsafe_steps,earliest_ttc_s,earliest_ttc_time_s\n";
  for (const measured_file& f : files) {
    for (const cr::measurement& m : f.outcome.measurements) {
      const measurement_summary sum = summarize(m);
      const bool ttc = std::isfinite(sum.earliest_ttc);
      text += fmt::format("{},{},{},{},{},{},{},{}\n", output::csv_field(f.name), m.agent, sum.steps, fixed(sum.least_room),
                          fixed(sum.least_room_time), sum.unsafe_steps,
                          ttc ? fixed(sum.earliest_ttc) : "", ttc ? fixed(sum.earliest_ttc_time) : "");
    }
  }
  return text;
}

std::string measurement_table(const measure_outcome& outcome) {
  std::string text = fmt::format("{:>10}  {:>5}  {:>10}  {:>8}  {:>12}  {:>8}  {:>8}\n", "road user", "steps",
                                 "least room", "at t [s]", "unsafe steps", "min TTC", "at t [s]");
  for (const cr::measurement& m : outcome.measurements) {
    const measurement_summary sum = summarize(m);
    const bool ttc = std::isfinite(sum.earliest_ttc);
    text += fmt::format("{:>10}  {:>5}  {:>10}  {:>8}  {:>12}  {:>8}  {:>8}\n", m.agent, sum.steps,
                        fixed(sum.least_room, 3), fixed(sum.least_room_time, 2), sum.unsafe_steps,
                        ttc ? fixed(sum.earliest_ttc, 2) : "-", ttc ? fixed(sum.earliest_ttc_time, 2) : "-");
  }
  return text;
}

}  // namespace mm::cli
