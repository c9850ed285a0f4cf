#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/scenario.hpp"
#include "mm/forecast_policy.hpp"

namespace mm::cli {

/// Options of `maneuvermap measure` once the CommonRoad file is read.
struct measure_settings {
  std::filesystem::path out_dir;  ///< created if missing; the five files are overwritten
  /// The road users to measure; empty: the recorded ego of the first planning problem that has one.
  std::vector<std::uint32_t> agents;
  bool every_road_user = false;  ///< `--agent all`: every road user that can be measured
  mm::forecast_policy policy;    ///< of every measured road user (spec §7)
  std::size_t jobs = 1;          ///< road users measured at a time (the files do not depend on it)
  /// `--on-lanelets`: the road constraint (spec §5) on the union of the file's lanelets.
  bool on_lanelets = false;
  std::ostream* progress = nullptr;  ///< where to show how many road users are done (a terminal), or null
};

/// What `maneuvermap measure` measured and wrote.
struct measure_outcome {
  std::vector<commonroad::measurement> measurements;  ///< one per road user, in the order measured
  std::vector<std::string> files;                     ///< the files written, in order
};

/// The road users `settings` asks for (throws input_error when none is given and the file has no
/// recorded ego, or when `every_road_user` finds none; `commonroad::measure_error` for an id that
/// cannot be measured).
std::vector<std::uint32_t> road_users_to_measure(const commonroad::scenario& s, const measure_settings& settings);

/// The road user that replays the ego of the file's first planning problem that has one
/// (`mm::commonroad::recorded_ego`), or none.
std::optional<std::uint32_t> planning_problem_ego(const commonroad::scenario& s);

/// Measures the road users of the recording `s` (named `name`, the file's stem) at every recorded
/// step and writes trajectories.csv, map.csv, decisions.csv, summary.json and scene.json into
/// `settings.out_dir`, in the formats of `maneuvermap run` (docs/outputs.md, docs/commonroad.md),
/// so that `maneuvermap plot` draws them, and rooms.csv: each step's room (`commonroad::room`). The files are a function of the recording and the
/// settings alone. Throws std::runtime_error when a file cannot be written.
measure_outcome measure_recording(const commonroad::scenario& s, const std::string& name,
                                  const measure_settings& settings);

/// One line per measured road user: its steps, its least room (max(MI−, MI+) at τ̄) and when, the
/// steps at which the planner would not have kept to what it did, and its earliest TTC.
std::string measurement_table(const measure_outcome& outcome);

/// One file of `maneuvermap measure FILE FILE...`: its name (the file's stem) and what was measured.
struct measured_file {
  std::string name;
  measure_outcome outcome;
};

/// measurements.csv of several measured files: the header
/// `file,agent,steps,least_room,least_room_time_s,unsafe_steps,earliest_ttc_s,earliest_ttc_time_s`,
/// then one row per measured road user, the files in the order given and each one's road users in
/// the order measured; the values of each file's summary.json (the TTC columns empty when the road
/// user was never on a collision course).
std::string measurements_csv(std::span<const measured_file> files);

}  // namespace mm::cli
