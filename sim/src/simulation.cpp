#include "mm/sim/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include "mm/number_text.hpp"
#include "sensing.hpp"
#include "worker_pool.hpp"

namespace mm::sim {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double kmh_per_ms = 3.6;
/// Offsets from the path up to this are "on the path" for the bypass metric (spec §12) [m].
constexpr double bypass_threshold = 0.1;

/// Margin [m] added to the planner's own reach when deciding which tracks to hand to it.
constexpr double relevance_slack = 5.0;
/// Extra time [s] beyond the history window during which a pair is tracked before it can matter.
constexpr double tracking_lead_time = 1.0;

/// Phases of a scripted agent mapped onto agent statuses.
agent_status status_of(motion_phase phase, before_start_behaviour before) {
  switch (phase) {
    case motion_phase::not_started:
      return before == before_start_behaviour::wait ? agent_status::waiting : agent_status::not_started;
    case motion_phase::moving: return agent_status::active;
    case motion_phase::stopped: return agent_status::stopped;
    case motion_phase::finished: return agent_status::finished;
  }
  return agent_status::finished;
}

mm::obstacle_kind obstacle_kind_of(agent_kind kind) {
  switch (kind) {
    case agent_kind::planning_vehicle:
    case agent_kind::scripted_vehicle: return mm::obstacle_kind::vehicle;
    case agent_kind::pedestrian: return mm::obstacle_kind::pedestrian;
    case agent_kind::static_obstacle: return mm::obstacle_kind::static_obstacle;
  }
  return mm::obstacle_kind::vehicle;
}

/// Farthest the ego can travel within the collision window: a_max over T_h, then straight at the
/// speed reached (the planner's own reach, spec §9).
double ego_reach(double speed, const mm::ego_limits& limits, const mm::planner_config& config) {
  return mm::travelled_distance(speed, limits.max_acceleration, config.displacement_horizon, limits.speed_cap) +
         mm::speed_after(speed, limits.max_acceleration, config.displacement_horizon, limits.speed_cap) *
             (config.collision_window - config.displacement_horizon);
}

/// Running metrics of one planning vehicle.
struct metrics_state {
  bool measured = false;  ///< at least one step counted
  double min_speed = inf;
  double max_speed = 0.0;
  double max_abs_offset = 0.0;
  double time_in_brake = 0.0;
  double time_in_accel = 0.0;
  std::size_t planning_steps = 0;
  std::vector<double> cpu_us;

  bool crash = false;
  double crash_time = 0.0;
  agent_id crash_with = 0;

  double min_gap = inf;
  double min_gap_time = 0.0;
  agent_id closest = 0;
  double speed_at_min = 0.0;
  double offset_at_min = 0.0;
  /// True states at the smallest gap, for the TTC (computed on demand).
  mm::pose own_pose;
  vec2 own_velocity;
  mm::pose other_pose;
  vec2 other_velocity;
};

}  // namespace

std::string_view to_string(agent_kind kind) {
  switch (kind) {
    case agent_kind::planning_vehicle: return "planning_vehicle";
    case agent_kind::scripted_vehicle: return "scripted_vehicle";
    case agent_kind::pedestrian: return "pedestrian";
    case agent_kind::static_obstacle: return "static_obstacle";
  }
  return "unknown";
}

std::string_view to_string(agent_status status) {
  switch (status) {
    case agent_status::not_started: return "not_started";
    case agent_status::waiting: return "waiting";
    case agent_status::active: return "active";
    case agent_status::stopped: return "stopped";
    case agent_status::crashed: return "crashed";
    case agent_status::finished: return "finished";
  }
  return "unknown";
}

bool is_present(agent_status status) {
  return status == agent_status::waiting || status == agent_status::active || status == agent_status::stopped ||
         status == agent_status::crashed;
}

struct simulation::impl {
  /// A planning vehicle's runtime: its command, plans, tracks and metrics.
  struct vehicle {
    const planning_vehicle* spec = nullptr;
    std::optional<tabulated_profile> desired_speed;  ///< `spec->desired_speed_profile`, tabulated
    maneuver command;
    /// Mode and family behind `command` (nominal for the follower's own u_nom).
    mm::planning_mode command_mode = mm::planning_mode::nominal;
    mm::family command_family = mm::family::brake;
    bool has_command = false;
    bool planned_now = false;
    std::optional<plan_record> last_plan;
    std::vector<detail::observation_ring> tracks;  ///< [target id]; with exact sensing only once crashed (frozen)
    /// With exact sensing: [target id] how many of the target's last observations (`observed`) this
    /// vehicle holds — consecutive steps in range, at most `track_capacity`.
    std::vector<std::uint32_t> seen;
    std::size_t track_capacity = 2;
    std::size_t estimate_window = 0;  ///< with exact sensing: its history window's index in `estimate_windows`
    bool frozen = false;  ///< crashed: its tracks were copied out of `observed` and no longer change
    std::vector<detail::noise_source> noise;       ///< [target id]
    metrics_state metrics;
  };

  /// The planners of one thread. A planner reuses what its previous plan sampled while the ego's
  /// speed (with its limits, footprint and horizon) is the same, and returns bit for bit what
  /// `mm::plan` returns whatever it planned before; so any vehicle may use any planner. The vehicles
  /// a thread plans share them by speed: the many that cruise at one speed plan with one planner,
  /// whose sampled sets and blocks stay in the cache from vehicle to vehicle, instead of each
  /// vehicle's own being fetched cold from memory.
  struct planner_set {
    static constexpr std::size_t capacity = 4;
    struct entry {
      double speed = 0.0;
      std::uint64_t last_use = 0;
      mm::planner planner;
    };
    std::vector<entry> entries;
    std::uint64_t uses = 0;
    /// The planner last used at this speed, else the least recently used one (or a new one).
    mm::planner& for_speed(double speed) {
      ++uses;
      entry* chosen = nullptr;
      for (entry& e : entries) {
        if (e.speed == speed) {
          chosen = &e;
          break;
        }
      }
      if (chosen == nullptr) {
        if (entries.size() < capacity) {
          chosen = &entries.emplace_back();
        } else {
          chosen = &*std::min_element(entries.begin(), entries.end(),
                                      [](const entry& a, const entry& b) { return a.last_use < b.last_use; });
        }
        chosen->speed = speed;
      }
      chosen->last_use = uses;
      return chosen->planner;
    }
  };

  struct scenario sc;
  run_options options;
  std::shared_ptr<const mm::drivable_area> area;  ///< of `sc.drivable_area`, built once; null without one
  std::vector<agent_info> infos;
  std::vector<agent_state> states;
  std::vector<double> radii;                       ///< bounding radius of each footprint [m]
  std::vector<std::optional<prepared_script>> scripts;  ///< per id; none for planning vehicles and statics
  /// A scripted vehicle with car following: whether it lags behind its script, and the
  /// acceleration it takes over the step (decided in `react` from the states at the step's start).
  struct lag {
    const scripted_vehicle* vehicle = nullptr;  ///< with car following; null: it keeps to its script
    bool lagging = false;
    double acceleration = 0.0;  ///< [m/s²]
  };
  std::vector<lag> lags;  ///< per id
  std::vector<agent_id> starting_to_lag;  ///< `react`'s
  std::vector<vehicle> vehicles;                   ///< ids 0..P−1
  std::unique_ptr<detail::worker_pool> pool;       ///< the helper threads of `decide` (jobs > 1), kept for the run
  std::vector<planner_set> planners;               ///< [thread of `decide`]
  /// Exact sensing (no noise): every observer sees the same states, so the observations are kept
  /// once per target (`observed`) instead of in a ring per observer and target; an observer holds
  /// only how many of them it has seen. The same histories, from memory that stays in the cache.
  bool exact_sensing = false;
  std::vector<detail::observation_ring> observed;  ///< [agent id], with exact sensing
  /// With exact sensing every observer that holds enough of a target's observations estimates the
  /// same motion from them: it is estimated once per step and target (and history window), and
  /// given to the planners as `obstacle_track::motion`. `used` is how many of the last
  /// observations the estimate reads (those within the window, at least two): an observer holding
  /// at least that many would estimate exactly this; one holding fewer estimates its own.
  struct shared_motion {
    std::size_t used = std::numeric_limits<std::size_t>::max();
    mm::motion_estimate motion;
  };
  std::vector<double> estimate_windows;       ///< the vehicles' distinct history windows [s]
  std::vector<shared_motion> shared_motions;  ///< [agent id · estimate_windows.size() + window]
  double shared_motion_time = std::numeric_limits<double>::quiet_NaN();  ///< when they were estimated [s]
  mm::obstacle_track estimate_scratch;
  std::vector<crash_event> crash_log;
  std::size_t step = 0;
  std::size_t last_step = 0;

  impl(struct scenario s, run_options run) : sc(std::move(s)), options(run) {
    if (auto error = validation_error(sc)) throw std::invalid_argument(*error);
    if (!sc.drivable_area.empty()) area = std::make_shared<const mm::drivable_area>(sc.drivable_area);
    last_step = static_cast<std::size_t>(std::ceil(sc.duration / sc.time_step - 1e-9));
    for (const planning_vehicle& v : sc.planning_vehicles) add(v.name, agent_kind::planning_vehicle, v.shape, nullptr);
    for (const scripted_vehicle& v : sc.scripted_vehicles) {
      add(v.name, agent_kind::scripted_vehicle, v.shape, &v.motion);
      if (v.car_following) lags.back().vehicle = &v;
    }
    for (const pedestrian& p : sc.pedestrians) add(p.name, agent_kind::pedestrian, mm::disc{p.radius}, &p.motion);
    for (const static_obstacle& o : sc.static_obstacles) {
      add(o.name, agent_kind::static_obstacle, static_footprint(o), nullptr);
      states.back().status = agent_status::active;
      states.back().pose = {static_reference_point(o), 0.0};
    }
    vehicles.resize(sc.planning_vehicles.size());
    for (std::size_t i = 0; i < vehicles.size(); ++i) {
      vehicle& v = vehicles[i];
      v.spec = &sc.planning_vehicles[i];
      if (v.spec->desired_speed_profile) v.desired_speed.emplace(*v.spec->desired_speed_profile);
      const double window = v.spec->planner.history_window;
      const auto capacity = static_cast<std::size_t>(std::floor(window / sc.time_step + 1e-9)) + 2;
      v.track_capacity = capacity;
      v.tracks.assign(infos.size(), detail::observation_ring(capacity));
      v.seen.assign(infos.size(), 0);
      for (const agent_info& target : infos) v.noise.emplace_back(sc.seed, infos[i].name, target.name);
    }
    const sensing_noise& noise = sc.noise;
    exact_sensing = !(noise.position_sd > 0.0 || noise.heading_sd > 0.0 || noise.speed_sd > 0.0);
    if (exact_sensing && !vehicles.empty()) {
      std::size_t capacity = 0;
      for (const vehicle& v : vehicles) capacity = std::max(capacity, v.track_capacity);
      observed.assign(infos.size(), detail::observation_ring(capacity));
      for (vehicle& v : vehicles) {
        const double window = v.spec->planner.history_window;
        const auto found = std::find(estimate_windows.begin(), estimate_windows.end(), window);
        v.estimate_window = static_cast<std::size_t>(found - estimate_windows.begin());
        if (found == estimate_windows.end()) estimate_windows.push_back(window);
      }
      shared_motions.resize(infos.size() * estimate_windows.size());
    }
    advance_agents(0.0, true);
    detect_crashes();
    measure();
    if (!ended()) {
      decide();
      react();
    }
  }

  void add(const std::string& name, agent_kind kind, mm::footprint shape, const scripted_motion* motion) {
    radii.push_back(mm::bounding_radius(shape));
    infos.push_back({name, kind, std::move(shape)});
    states.emplace_back();
    scripts.emplace_back();
    if (motion != nullptr) scripts.back().emplace(*motion);
    lags.emplace_back();
  }

  double now() const { return static_cast<double>(step) * sc.time_step; }

  bool ended() const {
    if (step >= last_step) return true;
    if (vehicles.empty()) return false;
    return std::all_of(vehicles.begin(), vehicles.end(), [&](const vehicle& v) {
      const agent_status s = states[id_of(v)].status;
      return s == agent_status::crashed || s == agent_status::finished;
    });
  }

  agent_id id_of(const vehicle& v) const { return static_cast<agent_id>(&v - vehicles.data()); }

  /// True once the clock has reached `start_time` (on the step grid, to rounding).
  bool started(double start_time) const { return now() >= start_time - 1e-9 * sc.time_step; }

  // --- 1. motion -------------------------------------------------------------------------------

  /// Moves every agent to the current time; `initial` places them at t = 0 instead.
  void advance_agents(double dt, bool initial) {
    for (vehicle& v : vehicles) advance_vehicle(v, dt, initial);
    for (agent_id id = vehicles.size(); id < infos.size(); ++id) {
      if (scripts[id]) advance_scripted(id, dt);
    }
  }

  void place_at_start(vehicle& v, agent_status status) {
    agent_state& s = states[id_of(v)];
    const planning_vehicle& spec = *v.spec;
    const path_point start = spec.path.at(spec.start_arc_length);
    s.status = status;
    s.pose = {start.position + spec.start_lateral_offset * unit_vector(start.heading + std::numbers::pi / 2.0),
              start.heading};
    s.speed = status == agent_status::active ? spec.initial_speed : 0.0;
    s.arc_length = spec.start_arc_length;
    s.lateral_offset = spec.start_lateral_offset;
    s.acceleration = 0.0;
    s.curvature = 0.0;
  }

  void advance_vehicle(vehicle& v, double dt, bool initial) {
    agent_state& s = states[id_of(v)];
    const planning_vehicle& spec = *v.spec;
    if (initial || s.status == agent_status::not_started || s.status == agent_status::waiting) {
      if (started(spec.start_time)) {
        place_at_start(v, agent_status::active);
      } else if (initial) {
        place_at_start(v, spec.before_start == before_start_behaviour::wait ? agent_status::waiting
                                                                            : agent_status::not_started);
      }
      return;
    }
    if (s.status != agent_status::active) return;
    if (v.command_mode != mm::planning_mode::nominal) {
      (v.command_family == mm::family::brake ? v.metrics.time_in_brake : v.metrics.time_in_accel) += dt;
    }
    const double cap = spec.limits.speed_cap;
    const mm::pose next = mm::maneuver_pose(s.pose, s.speed, v.command, dt, dt, cap);
    s.speed = mm::speed_after(s.speed, v.command.acceleration, dt, cap);
    s.pose = {next.position, wrap_angle(next.heading)};
    const path_projection p = spec.path.project(s.pose.position, s.arc_length, 5.0 + 2.0 * s.speed * dt);
    s.arc_length = p.arc_length;
    s.lateral_offset = p.lateral_offset;
    if (s.arc_length >= spec.path.length()) finish(v);
  }

  void finish(vehicle& v) {
    agent_state& s = states[id_of(v)];
    s.status = agent_status::finished;
    s.acceleration = 0.0;
    s.curvature = 0.0;
    v.planned_now = false;
    for (detail::observation_ring& ring : v.tracks) ring.clear();
    std::fill(v.seen.begin(), v.seen.end(), 0);
  }

  /// The script's mean acceleration over the coming step, (v(t + Δt) − v(t))/Δt [m/s²], where
  /// `now_sample` is its state at t: not the slope at t, because a replayed recording's speeds jump
  /// at its steps (within 10⁻⁷ s), and the slope there is no acceleration to take or to report.
  double acceleration_over_step(const prepared_script& script, const scripted_sample& now_sample) const {
    const double next = static_cast<double>(step + 1) * sc.time_step;
    return (script.state(next).speed - now_sample.speed) / sc.time_step;
  }

  struct lagged_move {
    double speed;       ///< [m/s]
    double arc_length;  ///< [m]
  };

  /// Speed and arc length of a lagging vehicle after a step of `dt` under its lag acceleration,
  /// stopping at rest; none once that would take it to its script at the step's end (`script_then`)
  /// or to its path's end, where it keeps to its script again.
  std::optional<lagged_move> lagged_step(agent_id id, const scripted_sample& script_then, double dt) const {
    const agent_state& s = states[id];
    const double a = lags[id].acceleration;
    double speed = s.speed + a * dt;
    double travelled = 0.5 * (s.speed + speed) * dt;
    if (speed < 0.0) {
      travelled = s.speed * s.speed / (-2.0 * a);
      speed = 0.0;
    }
    const double arc_length = s.arc_length + travelled;
    if (!(arc_length < script_then.arc_length && arc_length < scripts[id]->motion().path.length())) return std::nullopt;
    return lagged_move{speed, arc_length};
  }

  void advance_scripted(agent_id id, double dt) {
    agent_state& s = states[id];
    if (s.status == agent_status::crashed || s.status == agent_status::finished) return;
    const prepared_script& script = *scripts[id];
    const scripted_motion& m = script.motion();
    const scripted_sample sample = script.state(now());
    if (lags[id].lagging) {
      if (const std::optional<lagged_move> move = lagged_step(id, sample, dt)) {
        const path_point at = m.path.at(move->arc_length);
        s.status = agent_status::active;
        s.pose = {at.position, at.heading};
        s.speed = move->speed;
        s.curvature = at.curvature;
        s.arc_length = move->arc_length;
        s.lateral_offset = 0.0;
        return;
      }
      lags[id].lagging = false;  // caught up with its script (or at the path's end): on it again
    }
    const path_point where = m.path.at(sample.arc_length);
    s.status = status_of(sample.phase, m.before_start);
    s.pose = {where.position, where.heading};
    s.speed = sample.speed;
    s.acceleration = s.status == agent_status::active ? acceleration_over_step(script, sample) : 0.0;
    s.curvature = s.status == agent_status::active ? where.curvature : 0.0;
    s.arc_length = sample.arc_length;
    s.lateral_offset = 0.0;
  }

  /// Car following of the scripted vehicles that have it, from the states at the step's start (so
  /// that the order in which agents move does not matter): a vehicle on its script starts to lag
  /// when car following allows less than the script's acceleration over the step; a lagging one
  /// takes `lagging_acceleration`, which its state reports. Runs at the end of a step, after the
  /// decisions, on the states the next step starts from.
  void react() {
    // Who lags is read by the others' leader searches (`follows_scripted`): the vehicles that start
    // to lag this step are marked after every decision.
    starting_to_lag.clear();
    for (agent_id id = vehicles.size(); id < infos.size(); ++id) {
      lag& l = lags[id];
      if (l.vehicle == nullptr || states[id].status != agent_status::active) continue;
      const agent_state& s = states[id];
      const scripted_motion& m = l.vehicle->motion;
      const scripted_car_following& k = *l.vehicle->car_following;
      double cap = inf;
      if (const std::optional<leader> ahead = leader_of(id, m.path, l.vehicle->shape.length, k.following,
                                                        k.comfortable_deceleration, k.follows_scripted)) {
        cap = car_following_acceleration(s.speed, *ahead, k.following, k.max_acceleration, k.comfortable_deceleration);
      }
      scripted_sample script = scripts[id]->state(now());
      script.acceleration = acceleration_over_step(*scripts[id], script);
      if (!l.lagging) {
        if (!(cap < script.acceleration)) continue;
        starting_to_lag.push_back(id);
      }
      l.acceleration = lagging_acceleration(s.arc_length, s.speed, script, cap, k);
    }
    for (const agent_id id : starting_to_lag) lags[id].lagging = true;
    // What a lagging vehicle's state reports: its speed change over the coming step, on its lag or
    // back on its script.
    const double next = static_cast<double>(step + 1) * sc.time_step;
    for (agent_id id = vehicles.size(); id < infos.size(); ++id) {
      agent_state& s = states[id];
      if (!lags[id].lagging || s.status != agent_status::active) continue;
      const scripted_sample script_then = scripts[id]->state(next);
      const std::optional<lagged_move> move = lagged_step(id, script_then, sc.time_step);
      s.acceleration = ((move ? move->speed : script_then.speed) - s.speed) / sc.time_step;
    }
  }

  // --- 2. crashes ------------------------------------------------------------------------------

  /// Static obstacles never crash; the others crash once.
  bool can_crash(agent_id id) const {
    return states[id].status != agent_status::crashed && infos[id].kind != agent_kind::static_obstacle;
  }

  mm::placed_footprint placed(agent_id id) const { return mm::place(infos[id].shape, states[id].pose); }

  void detect_crashes() {
    for (agent_id i = 0; i < vehicles.size(); ++i) {
      if (!states[i].present()) continue;
      for (agent_id j = 0; j < infos.size(); ++j) {
        if (j == i || (j < vehicles.size() && j < i) || !states[j].present()) continue;
        if (!can_crash(i) && !can_crash(j)) continue;
        const double reach = radii[i] + radii[j];
        if (squared_norm(states[j].pose.position - states[i].pose.position) >= reach * reach) continue;
        if (!mm::overlaps(placed(i), placed(j))) continue;
        crash_log.push_back({now(), i, j});
        crash(i, j);
        crash(j, i);
      }
    }
  }

  /// `id` has overlapped `other`: it stops where it is, for good. Static obstacles are unaffected.
  void crash(agent_id id, agent_id other) {
    agent_state& s = states[id];
    if (s.status == agent_status::crashed || infos[id].kind == agent_kind::static_obstacle) return;
    if (id < vehicles.size()) {
      metrics_state& m = vehicles[id].metrics;
      if (s.status == agent_status::active) note_motion(m, s);
      m.crash = true;
      m.crash_time = now();
      m.crash_with = other;
      m.min_gap = 0.0;
      m.min_gap_time = now();
      m.closest = other;
      m.speed_at_min = s.speed;
      m.offset_at_min = s.lateral_offset;
      vehicles[id].command = {};
      vehicles[id].command_mode = mm::planning_mode::nominal;
      vehicles[id].planned_now = false;
      freeze_tracks(vehicles[id]);
    }
    s.status = agent_status::crashed;
    s.speed = 0.0;
    s.acceleration = 0.0;
    s.curvature = 0.0;
  }

  /// A crashed vehicle senses no more: with exact sensing its tracks are copied out of the shared
  /// observations now (which go on), as its own rings would have kept them.
  void freeze_tracks(vehicle& v) {
    if (!exact_sensing || v.frozen) return;
    v.frozen = true;
    std::vector<mm::observation> history;
    for (agent_id j = 0; j < infos.size(); ++j) {
      detail::observation_ring& ring = v.tracks[j];
      ring.clear();
      observed[j].copy_last_to(v.seen[j], history);
      for (const mm::observation& o : history) ring.push(o);
    }
  }

  // --- 3. metrics ------------------------------------------------------------------------------

  static void note_motion(metrics_state& m, const agent_state& s) {
    m.measured = true;
    m.min_speed = std::min(m.min_speed, s.speed);
    m.max_speed = std::max(m.max_speed, s.speed);
    m.max_abs_offset = std::max(m.max_abs_offset, std::abs(s.lateral_offset));
  }

  vec2 velocity(agent_id id) const { return states[id].speed * unit_vector(states[id].pose.heading); }

  void measure() {
    for (agent_id i = 0; i < vehicles.size(); ++i) {
      const agent_state& s = states[i];
      if (s.status != agent_status::active) continue;
      metrics_state& m = vehicles[i].metrics;
      note_motion(m, s);
      std::optional<mm::placed_footprint> own;
      for (agent_id j = 0; j < infos.size(); ++j) {
        if (j == i || !states[j].present()) continue;
        const double centres = norm(states[j].pose.position - s.pose.position);
        if (centres - radii[i] - radii[j] >= m.min_gap) continue;
        if (!own) own = placed(i);
        const double gap = mm::gap_distance(*own, placed(j));
        if (gap < m.min_gap) {
          m.min_gap = gap;
          m.min_gap_time = now();
          m.closest = j;
          m.speed_at_min = s.speed;
          m.offset_at_min = s.lateral_offset;
          m.own_pose = s.pose;
          m.own_velocity = velocity(i);
          m.other_pose = states[j].pose;
          m.other_velocity = velocity(j);
        }
      }
    }
  }

  // --- 4. sensing and decisions ----------------------------------------------------------------

  bool is_planner_relevant(const vehicle& v, agent_id target, double own_reach, double target_speed,
                           vec2 target_position) const {
    const agent_id i = id_of(v);
    const double reach = own_reach + target_speed * v.spec->planner.collision_window + radii[i] + radii[target] +
                         v.spec->planner.safety_margin + relevance_slack;
    return squared_norm(target_position - states[i].pose.position) < reach * reach;
  }

  /// Each present agent within tracking range is observed, with noise (into the pair's own ring) or
  /// exactly (counted: the target's shared ring holds the observation); the others are forgotten.
  void sense(vehicle& v) {
    const agent_id i = id_of(v);
    const planning_vehicle& spec = *v.spec;
    const agent_state& own = states[i];
    const double own_reach = ego_reach(own.speed, spec.limits, spec.planner);
    const double lead = spec.planner.history_window + tracking_lead_time;
    const sensing_noise& noise = sc.noise;
    for (agent_id j = 0; j < infos.size(); ++j) {
      if (j == i) continue;
      detail::observation_ring& ring = v.tracks[j];
      const agent_state& target = states[j];
      // In range when the pair could become relevant to the planner within the history window
      // plus a lead time, closing at most at v_cap + v_j + 1 m/s.
      const double closing = spec.limits.speed_cap + target.speed + 1.0;
      const bool in_range = target.present() &&
                            is_planner_relevant(v, j, own_reach + closing * lead, target.speed + 1.0,
                                                target.pose.position);
      if (!in_range) {
        ring.clear();
        v.seen[j] = 0;
        continue;
      }
      if (exact_sensing) {
        v.seen[j] = static_cast<std::uint32_t>(std::min<std::size_t>(v.seen[j] + 1, v.track_capacity));
        continue;
      }
      mm::observation o{now(), target.pose, target.speed};
      double n[4];
      v.noise[j].standard_normals(step, n);
      o.pose.position = o.pose.position + vec2{noise.position_sd * n[0], noise.position_sd * n[1]};
      o.pose.heading = wrap_angle(o.pose.heading + noise.heading_sd * n[2]);
      o.speed += noise.speed_sd * n[3];
      ring.push(o);
    }
  }

  /// Fills `input` with what vehicle `v` plans on now (u_nom given).
  void fill_input(const vehicle& v, const maneuver& nominal, mm::plan_input& input) const {
    const agent_id i = id_of(v);
    const planning_vehicle& spec = *v.spec;
    const agent_state& own = states[i];
    input.time = now();
    input.ego.pose = own.pose;
    input.ego.speed = own.speed;
    input.ego.shape = spec.shape;
    input.ego.limits = spec.limits;
    input.nominal = nominal;
    input.config = spec.planner;
    if (!options.map_columns || options.decision_only) input.config.map_column = false;
    input.config.decision_only = options.decision_only;  // whatever the vehicle's planner says: its plans are recorded
    input.drivable_area = area;
    const double own_reach = ego_reach(own.speed, spec.limits, spec.planner);
    std::size_t count = 0;
    const bool shared = exact_sensing && !v.frozen;
    for (agent_id j = 0; j < infos.size(); ++j) {
      // The vehicle's track of j: its own ring, or the last `seen[j]` of the shared observations.
      const detail::observation_ring& ring = shared ? observed[j] : v.tracks[j];
      const std::size_t size = shared ? v.seen[j] : ring.size();
      const mm::obstacle_kind kind = obstacle_kind_of(infos[j].kind);
      if (size < (kind == mm::obstacle_kind::static_obstacle ? 1U : 2U)) continue;
      const double max_speed = shared ? ring.max_speed_of_last(size) : ring.max_speed();
      if (!is_planner_relevant(v, j, own_reach, max_speed + 1.0, ring.back().pose.position)) continue;
      if (count == input.obstacles.size()) input.obstacles.emplace_back();
      mm::obstacle_track& track = input.obstacles[count++];
      track.id = static_cast<std::uint32_t>(j);
      track.kind = kind;
      track.shape = infos[j].shape;
      track.motion.reset();
      if (shared) {
        ring.copy_last_to(size, track.history);
        const shared_motion& motion = shared_motions[j * estimate_windows.size() + v.estimate_window];
        if (size >= motion.used && shared_motion_time == input.time) track.motion = motion.motion;
      } else {
        ring.copy_to(track.history);
      }
    }
    input.obstacles.resize(count);
  }

  follower_command nominal_of(const vehicle& v) const {
    const agent_state& s = states[id_of(v)];
    const planning_vehicle& spec = *v.spec;
    const double desired = v.desired_speed ? v.desired_speed->speed(now() - spec.start_time) : spec.desired_speed;
    follower_command command = follow_path(spec.path, s.arc_length, s.pose, s.speed, desired, spec.follower, spec.limits);
    if (spec.follower.car_following) {
      if (const std::optional<leader> ahead = leader_of(id_of(v), spec.path, spec.shape.length,
                                                        *spec.follower.car_following,
                                                        spec.follower.comfortable_deceleration, true)) {
        const double most = car_following_acceleration(s.speed, *ahead, *spec.follower.car_following,
                                                       spec.limits.max_acceleration,
                                                       spec.follower.comfortable_deceleration);
        if (most < command.nominal.acceleration) {
          command.nominal = clamp_to_limits({most, command.nominal.curvature}, s.speed, spec.limits);
        }
      }
    }
    return command;
  }

  /// The nearest road user ahead of vehicle `self` (of length `length` [m]) on its path — its
  /// reference point within the corridor beside the path, ahead of the vehicle's own projection and
  /// within a preview of 30 m + 3·(s0 + v·T) + v²/(2b), heading along the path within the largest
  /// heading difference; static obstacles are the planner's; without `scripted_too`, only road
  /// users that do not keep to a script (planning vehicles, lagging scripted vehicles) — with the
  /// gap from the vehicle's front to its rear along the path, and its speed along the path. From
  /// the true states: car following is part of the driver model, not of the planner's sensing.
  std::optional<leader> leader_of(agent_id self, const path& route, double length, const car_following_config& c,
                                  double comfortable_deceleration, bool scripted_too) const {
    const agent_state& me = states[self];
    const double v = me.speed;
    const double preview = 30.0 + 3.0 * (c.jam_distance + v * c.time_gap) + v * v / (2.0 * comfortable_deceleration);
    const double front = 0.5 * length;
    std::optional<leader> nearest;
    for (agent_id j = 0; j < states.size(); ++j) {
      const agent_state& other = states[j];
      if (j == self || !other.present() || infos[j].kind == agent_kind::static_obstacle) continue;
      if (!scripted_too && scripts[j] && !lags[j].lagging) continue;  // on its script
      const double reach = preview + front + radii[j];
      if (squared_norm(other.pose.position - me.pose.position) > reach * reach) continue;
      const path_projection p = route.project(other.pose.position, me.arc_length + 0.5 * preview, 0.5 * preview);
      if (p.distance > c.corridor_half_width || !(p.arc_length > me.arc_length)) continue;
      const vec2 along = unit_vector(p.nearest.heading);
      const double heading_along = dot(unit_vector(other.pose.heading), along);  // cos of the heading difference
      if (heading_along < std::cos(c.max_heading_difference)) continue;
      const mm::placed_footprint f = placed(j);
      double back = 0.0;  // how far its footprint reaches behind its reference point along the path
      for (std::size_t k = 0; k < f.vertex_count; ++k) back = std::max(back, dot(other.pose.position - f.vertices[k], along));
      const leader candidate{p.arc_length - me.arc_length - front - (back + f.radius),
                             other.speed * heading_along};
      if (!nearest || candidate.gap < nearest->gap) nearest = candidate;
    }
    return nearest;
  }

  /// Sensing and decisions of every planning vehicle. A vehicle reads the states of all agents
  /// (poses and speeds, which nothing changes here) and writes only its own runtime and its own
  /// command, so vehicles can be decided in any order, or in parallel.
  void decide() {
    if (exact_sensing && !vehicles.empty()) {
      // What every observer sees of each agent this step (`sense` then counts what it saw).
      for (agent_id j = 0; j < infos.size(); ++j) {
        const agent_state& target = states[j];
        if (target.present()) {
          observed[j].push({now(), target.pose, target.speed});
        } else {
          observed[j].clear();
        }
        estimate_shared_motion(j);
      }
      shared_motion_time = now();
    }
    const std::size_t jobs = std::min(std::max<std::size_t>(options.jobs, 1), vehicles.size());
    if (planners.size() < jobs) planners.resize(jobs);
    if (jobs <= 1) {
      for (vehicle& v : vehicles) decide(v, planners.front());
      return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> next_thread{0};
    std::vector<std::exception_ptr> errors(vehicles.size());
    const auto work = [&] {
      planner_set& own = planners[next_thread.fetch_add(1)];  // each call runs on its own thread
      for (std::size_t i = next.fetch_add(1); i < vehicles.size(); i = next.fetch_add(1)) {
        try {
          decide(vehicles[i], own);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    };
    if (!pool || pool->helpers() != jobs - 1) pool = std::make_unique<detail::worker_pool>(jobs - 1);
    pool->run(work);
    // The first failure in id order, whatever the threads' timing.
    for (const std::exception_ptr& error : errors) {
      if (error) std::rethrow_exception(error);
    }
  }

  /// `shared_motions` of target j, from its observations of this step (`estimate_motion`).
  void estimate_shared_motion(agent_id j) {
    const detail::observation_ring& ring = observed[j];
    const mm::obstacle_kind kind = obstacle_kind_of(infos[j].kind);
    const bool enough = ring.size() >= (kind == mm::obstacle_kind::static_obstacle ? 1U : 2U);
    if (enough) {
      estimate_scratch.kind = kind;
      ring.copy_to(estimate_scratch.history);
    }
    for (std::size_t w = 0; w < estimate_windows.size(); ++w) {
      shared_motion& shared = shared_motions[j * estimate_windows.size() + w];
      shared.used = std::numeric_limits<std::size_t>::max();
      if (!enough) continue;
      shared.used = mm::observations_read(estimate_scratch, estimate_windows[w]);
      shared.motion = mm::estimate_motion(estimate_scratch, estimate_windows[w], now());
    }
  }

  void decide(vehicle& v, planner_set& planners_of_thread) {
    v.planned_now = false;
    agent_state& s = states[id_of(v)];
    if (s.status == agent_status::waiting || s.status == agent_status::active) sense(v);
    if (s.status != agent_status::active) return;
    const maneuver nominal = nominal_of(v).nominal;
    if (!v.spec->avoidance) {
      v.command = nominal;
      v.command_mode = mm::planning_mode::nominal;
    } else if (!v.has_command || step % v.spec->planning_period == 0) {
      plan(v, nominal, planners_of_thread);
    }
    v.has_command = true;
    s.acceleration = v.command.acceleration;
    s.curvature = v.command.curvature;
  }

  void plan(vehicle& v, const maneuver& nominal, planner_set& planners_of_thread) {
    // One input buffer per thread, not per vehicle: filled for vehicle after vehicle, its memory
    // (the obstacles' histories) stays in the cache instead of being fetched cold for each vehicle.
    // `fill_input` sets every field.
    thread_local mm::plan_input input;
    fill_input(v, nominal, input);
    plan_record record;
    record.time = now();
    if (options.measure_cpu_time) {
      const auto start = std::chrono::steady_clock::now();
      record.result = planners_of_thread.for_speed(input.ego.speed).plan(input);
      const auto stop = std::chrono::steady_clock::now();
      record.cpu_time_us = std::chrono::duration<double, std::micro>(stop - start).count();
      v.metrics.cpu_us.push_back(record.cpu_time_us);
    } else {
      record.result = planners_of_thread.for_speed(input.ego.speed).plan(input);
    }
    if (!record.result.ok()) {
      throw std::logic_error("planning vehicle \"" + infos[id_of(v)].name + "\" at t = " + number_text(now()) +
                             " s: mm::plan rejected its input: " + record.result.error);
    }
    ++v.metrics.planning_steps;
    v.command = record.result.command;
    v.command_mode = record.result.mode;
    v.command_family = record.result.selected_family;
    v.planned_now = true;
    v.last_plan = std::move(record);
  }

  // --- results ---------------------------------------------------------------------------------

  run_metrics metrics_of(agent_id id) const {
    const metrics_state& m = vehicles[id].metrics;
    run_metrics r;
    r.agent = infos[id].name;
    r.crash = m.crash;
    if (m.crash) {
      r.crash_time_s = m.crash_time;
      r.crash_with = infos[m.crash_with].name;
    }
    if (m.min_gap < inf) {
      r.min_dist_m = m.min_gap;
      r.min_dist_time_s = m.min_gap_time;
      r.closest_agent = infos[m.closest].name;
      r.speed_kmh = m.speed_at_min * kmh_per_ms;
      r.lateral_offset_at_min_m = m.offset_at_min;
      if (!m.crash) {
        r.ttc_at_min_s = constant_velocity_ttc(infos[id].shape, m.own_pose, m.own_velocity, infos[m.closest].shape,
                                               m.other_pose, m.other_velocity);
      }
    }
    r.max_lateral_offset_m = m.max_abs_offset;
    if (m.max_abs_offset > bypass_threshold && m.min_gap < inf) {
      r.bypass = m.offset_at_min > 0.0 ? bypass_side::left
                 : m.offset_at_min < 0.0 ? bypass_side::right
                                         : bypass_side::none;
    }
    if (m.measured) {
      r.min_speed_kmh = m.min_speed * kmh_per_ms;
      r.max_speed_kmh = m.max_speed * kmh_per_ms;
    }
    r.time_in_brake_s = m.time_in_brake;
    r.time_in_accel_s = m.time_in_accel;
    r.planning_steps = m.planning_steps;
    r.cpu_median_us = quantile(m.cpu_us, 0.5);
    r.cpu_p99_us = quantile(m.cpu_us, 0.99);
    return r;
  }
};

simulation::simulation(struct scenario s, run_options options)
    : impl_(std::make_unique<impl>(std::move(s), options)) {}
simulation::~simulation() = default;
simulation::simulation(simulation&&) noexcept = default;
simulation& simulation::operator=(simulation&&) noexcept = default;

void simulation::step() {
  impl& m = *impl_;
  if (m.ended()) return;
  ++m.step;
  m.advance_agents(m.sc.time_step, false);
  m.detect_crashes();
  m.measure();
  if (m.ended()) {
    for (impl::vehicle& v : m.vehicles) v.planned_now = false;
    return;
  }
  m.decide();
  m.react();
}

bool simulation::ended() const { return impl_->ended(); }
double simulation::time() const { return impl_->now(); }
std::size_t simulation::step_index() const { return impl_->step; }
const struct scenario& simulation::definition() const { return impl_->sc; }
std::size_t simulation::agent_count() const { return impl_->infos.size(); }
std::size_t simulation::planning_vehicle_count() const { return impl_->vehicles.size(); }
namespace {

/// `id`, or std::out_of_range naming it and the ids there are (`what`: "agent", "planning vehicle").
agent_id checked(agent_id id, std::size_t count, const char* what, const char* call) {
  if (id >= count) {
    throw std::out_of_range(std::string(call) + ": " + what + " " + std::to_string(id) + " does not exist: expected " +
                            (count == 0 ? std::string("none, the scenario has no ") + what
                                        : "an id from 0 to " + std::to_string(count - 1)));
  }
  return id;
}

}  // namespace

const agent_info& simulation::info(agent_id id) const {
  return impl_->infos[checked(id, impl_->infos.size(), "agent", "info")];
}
const agent_state& simulation::state(agent_id id) const {
  return impl_->states[checked(id, impl_->states.size(), "agent", "state")];
}
std::span<const agent_state> simulation::states() const { return impl_->states; }

std::optional<agent_id> simulation::find(std::string_view name) const {
  for (agent_id id = 0; id < impl_->infos.size(); ++id) {
    if (impl_->infos[id].name == name) return id;
  }
  return std::nullopt;
}

const plan_record* simulation::last_plan(agent_id id) const {
  const auto& v = impl_->vehicles[checked(id, impl_->vehicles.size(), "planning vehicle", "last_plan")];
  return v.last_plan ? &*v.last_plan : nullptr;
}

bool simulation::planned_now(agent_id id) const {
  return impl_->vehicles[checked(id, impl_->vehicles.size(), "planning vehicle", "planned_now")].planned_now;
}

void simulation::override_command(agent_id id, const mm::maneuver& u) {
  impl::vehicle& v = impl_->vehicles[checked(id, impl_->vehicles.size(), "planning vehicle", "override_command")];
  agent_state& s = impl_->states[id];
  const std::string who = "override_command: planning vehicle \"" + impl_->infos[id].name + "\"";
  if (s.status != agent_status::active) {
    throw std::invalid_argument(who + " is " + std::string(to_string(s.status)) +
                                ": only an active vehicle takes a command");
  }
  if (auto why = command_error(*v.spec, s.speed, u)) throw std::invalid_argument(who + ": " + *why);
  v.command = u;
  s.acceleration = u.acceleration;
  s.curvature = u.curvature;
}

std::optional<mm::plan_input> simulation::planning_input(agent_id id) const {
  const impl::vehicle& v = impl_->vehicles[checked(id, impl_->vehicles.size(), "planning vehicle", "planning_input")];
  if (!impl_->states[id].present()) return std::nullopt;
  mm::plan_input input;
  impl_->fill_input(v, impl_->nominal_of(v).nominal, input);
  return input;
}

std::span<const crash_event> simulation::crashes() const { return impl_->crash_log; }

run_metrics simulation::metrics(agent_id id) const {
  return impl_->metrics_of(checked(id, impl_->vehicles.size(), "planning vehicle", "metrics"));
}

std::vector<run_metrics> simulation::all_metrics() const {
  std::vector<run_metrics> all;
  for (agent_id id = 0; id < impl_->vehicles.size(); ++id) all.push_back(impl_->metrics_of(id));
  return all;
}

void run(simulation& sim, const std::function<void(const simulation&)>& observe) {
  if (observe) observe(sim);
  while (!sim.ended()) {
    sim.step();
    if (observe) observe(sim);
  }
}

}  // namespace mm::sim
