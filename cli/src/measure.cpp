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
#include "mm/commonroad/reader.hpp"
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

json summary_json(const cr::scenario& s, const std::string& name, const measure_settings& settings,
                  const std::vector<road_user_summary>& road_users) {
  const auto [first, last] = step_range(s);
  json vehicles = json::array();
  for (const road_user_summary& sum : road_users) {
    vehicles.push_back({{"agent", name_of(sum.agent)},
                        {"steps", sum.steps},
                        {"steps_on_drivable_area", sum.steps_on_drivable_area},
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
  if (!settings.agents.empty()) {
    for (const std::uint32_t agent : settings.agents) cr::require_measurable(s, agent);
    return settings.agents;
  }
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

road_user_summary summarize(const cr::measurement& m) {
  road_user_summary sum;
  sum.agent = m.agent;
  sum.steps = m.steps.size();
  for (const cr::measured_step& step : m.steps) {
    const double room = cr::room(step.result);
    if (&step == &m.steps.front() || room < sum.least_room) {
      sum.least_room = room;
      sum.least_room_time = step.time;
    }
    if (step.result.mode != mm::planning_mode::nominal) ++sum.unsafe_steps;
    if (step.result.on_drivable_area) ++sum.steps_on_drivable_area;
    if (step.result.time_to_collision < sum.earliest_ttc) {
      sum.earliest_ttc = step.result.time_to_collision;
      sum.earliest_ttc_time = step.time;
    }
  }
  return sum;
}

namespace {

/// The road constraint of `--on-lanelets`: the union of the file's lanelets; none without it.
std::shared_ptr<const drivable_area> drivable_area_of(const cr::scenario& s, const measure_settings& settings) {
  if (!settings.on_lanelets) return nullptr;
  try {
    return std::make_shared<const drivable_area>(cr::lanelet_polygons(s));
  } catch (const std::invalid_argument& e) {
    throw input_error(std::string("--on-lanelets: ") + e.what());
  }
}

/// Writes the six files of one measured recording into `out_dir`; returns their paths.
std::vector<std::string> write_measurement(const cr::scenario& s, const std::string& name,
                                           const std::filesystem::path& out_dir, const measure_settings& settings,
                                           std::span<const cr::measurement> measurements,
                                           const std::vector<road_user_summary>& road_users,
                                           const std::shared_ptr<const drivable_area>& area) {
  // map.csv and decisions.csv by time, then road user, as `maneuvermap run` writes them.
  struct row_key {
    double time;
    std::size_t measurement;
    std::size_t step;
  };
  std::vector<row_key> keys;
  for (std::size_t m = 0; m < measurements.size(); ++m) {
    for (std::size_t k = 0; k < measurements[m].steps.size(); ++k) keys.push_back({measurements[m].steps[k].time, m, k});
  }
  std::stable_sort(keys.begin(), keys.end(), [](const row_key& a, const row_key& b) { return a.time < b.time; });
  std::string map = "t,agent,tau,mi_brake,mi_accel,excluded\n";
  std::string decisions = "t,agent,tau_bar,family,mode,ttc,cpu_us,robust\n";
  std::string rooms = "t,agent,speed,room,mode,ttc\n";
  for (const row_key& key : keys) {
    const cr::measured_step& step = measurements[key.measurement].steps[key.step];
    const plan_result& r = step.result;
    const std::string prefix = fixed(step.time) + ',' + name_of(measurements[key.measurement].agent) + ',';
    for (std::size_t i = 0; i < r.mi_brake.size(); ++i) {  // none without a map column
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

  std::vector<std::string> written;
  std::filesystem::create_directories(out_dir);
  const auto write = [&](const char* file, const std::string& text) {
    output::write_text(out_dir / file, text);
    written.push_back((out_dir / file).string());
  };
  write("trajectories.csv", trajectories_csv(s));
  write("map.csv", map);
  write("decisions.csv", decisions);
  write("summary.json", summary_json(s, name, settings, road_users).dump(2) + "\n");
  std::vector<std::uint32_t> measured;
  for (const road_user_summary& sum : road_users) measured.push_back(sum.agent);
  write("scene.json", scene_json(s, name, measured, area).dump() + "\n");
  write("rooms.csv", rooms);
  return written;
}

/// One file in the pool of `measure_files`: its road users, and while some are measured, the
/// recording, its drivable area and their measurements.
struct file_work {
  const measure_request* request = nullptr;
  std::vector<std::uint32_t> agents;
  std::size_t first_task = 0;  ///< its road users are tasks first_task, first_task + 1, ...
  std::mutex mutex;            ///< guards the loading and release of `recording` and `area`
  std::shared_ptr<const cr::scenario> recording;
  std::shared_ptr<const drivable_area> area;
  std::vector<cr::measurement> measurements;
  std::atomic<std::size_t> remaining{0};
  std::exception_ptr write_error;
  measured_file result;
};

/// "FILE: why" of an error found before measuring (a read_error names the file itself).
std::string unmeasurable(const measure_request& request) {
  try {
    throw;
  } catch (const cr::read_error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return request.file + ": " + e.what();
  }
}

}  // namespace

std::vector<measured_file> measure_files(std::span<const measure_request> requests, const measure_settings& settings) {
  // Every file read and checked before anything is measured: all the files that cannot be, at once.
  std::vector<std::unique_ptr<file_work>> work;
  std::vector<std::string> problems;
  bool no_ego = false;
  for (const measure_request& request : requests) {
    auto& f = *work.emplace_back(std::make_unique<file_work>());
    f.request = &request;
    try {
      auto recording = std::make_shared<const cr::scenario>(cr::read_scenario(request.file));
      if (settings.agents.empty() && !settings.every_road_user && !planning_problem_ego(*recording) &&
          requests.size() > 1) {
        // One line each; the hint once, below.
        no_ego = true;
        problems.push_back(request.file + ": no obstacle of the file replays the ego of its planning problem");
        continue;
      }
      f.agents = road_users_to_measure(*recording, settings);
      auto area = drivable_area_of(*recording, settings);
      // The first files are measured first: those the threads start on are kept, not read again.
      if (work.size() <= settings.jobs) {
        f.recording = std::move(recording);
        f.area = std::move(area);
      }
    } catch (const std::exception&) {
      problems.push_back(unmeasurable(request));
    }
  }
  if (problems.size() == 1 && requests.size() == 1) throw input_error(problems.front());
  if (!problems.empty()) {
    std::string message = fmt::format("{} of the {} files cannot be measured; nothing was measured:", problems.size(),
                                      requests.size());
    for (const std::string& p : problems) message += "\n  " + p;
    if (no_ego) message += "\nwith several files, --agent all measures every road user of each";
    throw input_error(message);
  }

  // One pool over the road users of every file, file after file.
  struct task {
    std::size_t file;
    std::size_t road_user;
  };
  std::vector<task> tasks;
  for (std::size_t k = 0; k < work.size(); ++k) {
    file_work& f = *work[k];
    f.first_task = tasks.size();
    f.measurements.resize(f.agents.size());
    f.remaining = f.agents.size();
    for (std::size_t i = 0; i < f.agents.size(); ++i) tasks.push_back({k, i});
  }
  std::vector<std::exception_ptr> errors(tasks.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;
  const auto finish = [&](file_work& f) {
    // Its last road user is done: its files written (unless one failed), then it is released.
    const bool failed = std::any_of(errors.begin() + static_cast<std::ptrdiff_t>(f.first_task),
                                    errors.begin() + static_cast<std::ptrdiff_t>(f.first_task + f.agents.size()),
                                    [](const std::exception_ptr& e) { return e != nullptr; });
    if (!failed) {
      try {
        measured_file& r = f.result;
        r.name = f.request->name;
        r.commonroad_version = f.recording->version;
        r.obstacles = f.recording->obstacles.size();
        r.time_step = f.recording->time_step;
        for (const cr::measurement& m : f.measurements) r.road_users.push_back(summarize(m));
        r.files = write_measurement(*f.recording, r.name, f.request->out_dir, settings, f.measurements, r.road_users,
                                    f.area);
      } catch (...) {
        f.write_error = std::current_exception();
      }
    }
    const std::lock_guard lock(f.mutex);
    f.recording.reset();
    f.area.reset();
    std::vector<cr::measurement>().swap(f.measurements);
  };
  const auto worker = [&] {
    cr::measure_options options;
    options.config.policy = settings.policy;
    for (std::size_t t = next++; t < tasks.size(); t = next++) {
      file_work& f = *work[tasks[t].file];
      try {
        std::shared_ptr<const cr::scenario> recording;
        {
          const std::lock_guard lock(f.mutex);
          if (!f.recording) {
            f.recording = std::make_shared<const cr::scenario>(cr::read_scenario(f.request->file));
            f.area = drivable_area_of(*f.recording, settings);
          }
          recording = f.recording;
          options.drivable_area = f.area;
        }
        options.agent = f.agents[tasks[t].road_user];
        f.measurements[tasks[t].road_user] = cr::measure(*recording, options);
      } catch (const cr::measure_error& e) {
        errors[t] = std::make_exception_ptr(cr::measure_error(f.request->file + ": " + e.what()));
      } catch (const input_error& e) {
        errors[t] = std::make_exception_ptr(input_error(f.request->file + ": " + e.what()));
      } catch (...) {
        errors[t] = std::current_exception();
      }
      if (settings.progress != nullptr) {
        const std::lock_guard lock(progress_mutex);
        *settings.progress << fmt::format("\r{}: {} / {} road users measured", f.request->name, ++done, tasks.size())
                           << std::flush;
      }
      if (--f.remaining == 0) finish(f);
    }
  };
  {
    std::vector<std::jthread> threads;
    for (std::size_t j = 1; j < std::min(settings.jobs, tasks.size()); ++j) threads.emplace_back(worker);
    worker();
  }
  if (settings.progress != nullptr) *settings.progress << "\r\033[K" << std::flush;
  // The first error, in the order of the files and their road users.
  std::vector<measured_file> results;
  for (const auto& f : work) {
    for (std::size_t i = 0; i < f->agents.size(); ++i) {
      if (errors[f->first_task + i]) std::rethrow_exception(errors[f->first_task + i]);
    }
    if (f->write_error) std::rethrow_exception(f->write_error);
    results.push_back(std::move(f->result));
  }
  return results;
}

std::string measurements_csv(std::span<const measured_file> files) {
  std::string text = "file,agent,steps,least_room,least_room_time_s,unsafe_steps,earliest_ttc_s,earliest_ttc_time_s\n";
  for (const measured_file& f : files) {
    for (const road_user_summary& sum : f.road_users) {
      const bool ttc = std::isfinite(sum.earliest_ttc);
      text += fmt::format("{},{},{},{},{},{},{},{}\n", output::csv_field(f.name), sum.agent, sum.steps, fixed(sum.least_room),
                          fixed(sum.least_room_time), sum.unsafe_steps,
                          ttc ? fixed(sum.earliest_ttc) : "", ttc ? fixed(sum.earliest_ttc_time) : "");
    }
  }
  return text;
}

std::string measurement_table(const measured_file& file) {
  std::string text = fmt::format("{:>10}  {:>5}  {:>10}  {:>8}  {:>12}  {:>8}  {:>8}\n", "road user", "steps",
                                 "least room", "at t [s]", "unsafe steps", "min TTC", "at t [s]");
  for (const road_user_summary& sum : file.road_users) {
    const bool ttc = std::isfinite(sum.earliest_ttc);
    text += fmt::format("{:>10}  {:>5}  {:>10}  {:>8}  {:>12}  {:>8}  {:>8}\n", sum.agent, sum.steps,
                        fixed(sum.least_room, 3), fixed(sum.least_room_time, 2), sum.unsafe_steps,
                        ttc ? fixed(sum.earliest_ttc, 2) : "-", ttc ? fixed(sum.earliest_ttc_time, 2) : "-");
  }
  return text;
}

}  // namespace mm::cli
