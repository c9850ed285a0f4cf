#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mm/planner.hpp"
#include "mm/sim/metrics.hpp"
#include "mm/sim/scenario.hpp"

namespace mm::sim {

/// Index of an agent in a simulation: planning vehicles first (ids 0..P−1, in scenario order),
/// then scripted vehicles, pedestrians and static obstacles. Also the `obstacle_track::id` under
/// which the other agents see it.
using agent_id = std::size_t;

enum class agent_kind : std::uint8_t { planning_vehicle, scripted_vehicle, pedestrian, static_obstacle };

std::string_view to_string(agent_kind kind);

/// Where an agent is in its life.
enum class agent_status : std::uint8_t {
  not_started,  ///< before its start time and absent: not observed, not collidable
  waiting,      ///< before its start time, standing at its start pose (`before_start_behaviour::wait`)
  active,       ///< moving (static obstacles are always active)
  stopped,      ///< a scripted agent standing at its stop
  crashed,      ///< overlapped another agent; stands still for the rest of the run, still an obstacle
  finished,     ///< reached the end of its path and left the scene: not observed, not collidable
};

std::string_view to_string(agent_status status);

/// True for the statuses in which an agent is in the world: observed and collidable.
bool is_present(agent_status status);

/// The fixed description of an agent.
struct agent_info {
  std::string name;
  agent_kind kind = agent_kind::planning_vehicle;
  mm::footprint shape;  ///< about its reference point
};

/// The true state of an agent at the current time, and what it does over the coming step.
struct agent_state {
  agent_status status = agent_status::not_started;
  mm::pose pose;               ///< reference point [m] and heading [rad], wrapped to (−π, π]
  double speed = 0.0;          ///< [m/s]
  double acceleration = 0.0;   ///< applied from now over the coming step [m/s²]
  double curvature = 0.0;      ///< path curvature applied over the coming step [1/m], left positive
  double arc_length = 0.0;     ///< s on its path [m]: the projection for a planning vehicle; 0 for static
  double lateral_offset = 0.0; ///< from its path [m], left positive; 0 for scripted and static agents

  bool present() const { return is_present(status); }
};

/// The last planning step of a planning vehicle.
struct plan_record {
  double time = 0.0;       ///< when it planned [s]
  mm::plan_result result;  ///< the map column, τ̄, family, mode, TTC and command (spec §6–§8)
  double cpu_time_us = 0.0;  ///< wall-clock time of the `mm::plan` call [µs]; 0 unless measured
};

/// An overlap of two agents' footprints, of which at least one is a planning vehicle.
struct crash_event {
  double time = 0.0;  ///< [s]
  agent_id first = 0;   ///< the planning vehicle (the smaller id if both are)
  agent_id second = 0;
};

/// Options of a run that are not part of the scenario.
struct run_options {
  /// Time every `mm::plan` call with a steady clock (run_metrics::cpu_*_us, plan_record::cpu_time_us).
  /// Off by default so that the same scenario and seed give bit-identical outputs.
  bool measure_cpu_time = false;
  /// Threads that sense and plan the planning vehicles of a step in parallel (1: the calling
  /// thread only; 0 means 1). Each vehicle's decision depends only on the states at the start of
  /// the step, so any value gives bit-identical outputs.
  std::size_t jobs = 1;
  /// Compute the column of the Maneuverability Map at every planning step (`mm::planner_config::
  /// map_column`, `plan_record::result.mi_brake`/`mi_accelerate`). Off for runs whose maps nobody
  /// reads, such as a sweep's: only the forecast times the decisions read are evaluated, and every
  /// decision, so the whole run, is the same, bit for bit.
  bool map_columns = true;
  /// Plan with `mm::planner_config::decision_only` (and without the map columns): a step whose
  /// nominal maneuver is proven safe under every forecast time returns it without the indices.
  /// Every command, so the whole run and its metrics, is the same, bit for bit; the plan records
  /// of such steps have `indices_computed` false (no τ̄, family or selected indices). For runs whose
  /// decisions nobody reads but through the metrics, such as a sweep's. It alone decides: a planning
  /// vehicle's own `planner.decision_only` is not read, so that the records a run writes have their
  /// indices unless the run asks otherwise.
  bool decision_only = false;
};

/// A run of a scenario on a fixed time grid t_k = k·dt (pure computation, no I/O).
///
/// Construction places every agent at t = 0 and makes the first decisions; each `step()` then
/// moves from t_k to t_{k+1} (see docs/simulator.md for the data flow):
/// 1. motion: every moving agent advances over dt — planning vehicles integrate their command
///    (a, κ) exactly (`mm::maneuver_pose`, `mm::speed_after`) and re-project onto their path;
///    scripted agents take their closed-form state at t_{k+1}; agents start and finish;
/// 2. crashes: every overlap involving a planning vehicle becomes a crash (both parties stop);
/// 3. metrics of every planning vehicle (gaps, speeds, offsets);
/// 4. unless the run has ended: sensing (each planning vehicle observes every other present agent
///    within tracking range, with noise) and decisions (u_nom by the path follower, then
///    `mm::plan` on every k-th step, or u_nom itself when `avoidance` is off).
/// After construction and after each step the accessors describe one coherent instant: the
/// states at `time()`, the commands applied from `time()`, and the plans made at `time()`.
///
/// Not thread-safe; const members may be called concurrently with each other.
class simulation {
 public:
  /// Throws std::invalid_argument with `validation_error(s)` when the scenario is invalid.
  explicit simulation(scenario s, run_options options = {});
  ~simulation();
  simulation(simulation&&) noexcept;
  simulation& operator=(simulation&&) noexcept;
  simulation(const simulation&) = delete;
  simulation& operator=(const simulation&) = delete;

  /// Advances one time step. No-op once `ended()`.
  void step();

  /// True when the time has reached the duration, or when every planning vehicle (if there is
  /// one) has crashed or finished its path. At the instant the run ends nothing is sensed or
  /// planned: `planned_now` is false and the tracks hold the previous step's observations.
  bool ended() const;

  double time() const;               ///< t_k [s]
  std::size_t step_index() const;    ///< k
  const struct scenario& definition() const;  ///< the scenario being run

  std::size_t agent_count() const;
  std::size_t planning_vehicle_count() const;  ///< their ids are 0..count−1
  const agent_info& info(agent_id id) const;
  const agent_state& state(agent_id id) const;
  std::span<const agent_state> states() const;
  std::optional<agent_id> find(std::string_view name) const;

  /// The last planning step of planning vehicle `id`, or null if it has not planned yet.
  const plan_record* last_plan(agent_id id) const;
  /// True when planning vehicle `id` called `mm::plan` at the current time.
  bool planned_now(agent_id id) const;

  /// The input planning vehicle `id` plans on at the current time: its state, u_nom and its
  /// tracks of the agents within range that have enough observations (two; one for static
  /// obstacles) — e.g. to re-plan with `config.record_samples = true` for a snapshot. None when
  /// the vehicle is not in the world.
  std::optional<mm::plan_input> planning_input(agent_id id) const;

  /// Drives planning vehicle `id` with `u` from the current time until its next decision (the next
  /// step, or the next planning step with a `planning_period` above 1) instead of the command it
  /// decided: a controller of the caller's in the loop, e.g. another planner run on
  /// `planning_input(id)`. The vehicle still senses and plans as before (its plans, map and
  /// `time_in_brake`/`time_in_accel` stay its own planner's); `state(id)` shows `u` as the command
  /// applied from now. Throws std::out_of_range for an id that is not a planning vehicle, and
  /// std::invalid_argument, naming the vehicle, the field and its value, when the vehicle is not
  /// active or `u` is outside its limits: a ∈ [−d_max, a_max] and |κ| ≤ κ_max(v) (spec §3).
  void override_command(agent_id id, const mm::maneuver& u);

  /// Every crash so far, in time order.
  std::span<const crash_event> crashes() const;

  /// The run metrics of planning vehicle `id` so far (spec §12).
  run_metrics metrics(agent_id id) const;
  /// The run metrics of every planning vehicle, in id order.
  std::vector<run_metrics> all_metrics() const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

/// Runs `sim` to its end, calling `observe` once for the current instant and once after every
/// step (e.g. to write trajectories, maps and decisions).
void run(simulation& sim, const std::function<void(const simulation&)>& observe = {});

}  // namespace mm::sim
