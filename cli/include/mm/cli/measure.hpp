#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/scenario.hpp"
#include "mm/forecast_policy.hpp"

namespace mm::cli {

/// Options of `maneuvermap measure`.
struct measure_settings {
  /// The road users to measure; empty: the recorded ego of the first planning problem that has one.
  std::vector<std::uint32_t> agents;
  bool every_road_user = false;  ///< `--agent all`: every road user that can be measured
  mm::forecast_policy policy;    ///< of every measured road user (spec §7)
  std::size_t jobs = 1;          ///< road users measured at a time (the files do not depend on it)
  /// `--on-lanelets`: the road constraint (spec §5) on the union of the file's lanelets.
  bool on_lanelets = false;
  std::ostream* progress = nullptr;  ///< where to show how many road users are done (a terminal), or null
};

/// The road users `settings` asks for (throws input_error when none is given and the file has no
/// recorded ego, or when `every_road_user` finds none; `commonroad::measure_error` for an id that
/// cannot be measured).
std::vector<std::uint32_t> road_users_to_measure(const commonroad::scenario& s, const measure_settings& settings);

/// The road user that replays the ego of the file's first planning problem that has one
/// (`mm::commonroad::recorded_ego`), or none.
std::optional<std::uint32_t> planning_problem_ego(const commonroad::scenario& s);

/// What `maneuvermap measure` found for one road user: the values of its row in summary.json.
struct road_user_summary {
  std::uint32_t agent = 0;
  std::size_t steps = 0;
  std::size_t steps_on_drivable_area = 0;  ///< steps at which the road constraint bound it
  double least_room = 1.0;                 ///< max(MI−, MI+) at τ̄, smallest over the steps
  double least_room_time = 0.0;            ///< [s]
  std::size_t unsafe_steps = 0;            ///< planning mode not nominal: what it did was not safe (spec §8)
  double earliest_ttc = std::numeric_limits<double>::infinity();  ///< [s], ∞ when never on a collision course
  double earliest_ttc_time = 0.0;                                 ///< [s]
};

/// `road_user_summary` of a measurement.
road_user_summary summarize(const commonroad::measurement& m);

/// One CommonRoad file to measure: the file, its name (its stem) and where its outputs go.
struct measure_request {
  std::string file;
  std::string name;
  std::filesystem::path out_dir;
};

/// What `maneuvermap measure` measured in one file and wrote.
struct measured_file {
  std::string name;
  std::string commonroad_version;
  std::size_t obstacles = 0;  ///< road users and obstacles in the file
  double time_step = 0.0;     ///< [s]
  std::vector<road_user_summary> road_users;  ///< in the order measured
  std::vector<std::string> files;             ///< the files written, in order
};

/// Measures the road users of the CommonRoad files of `requests` at every recorded step and writes,
/// into each file's `out_dir`, trajectories.csv, map.csv, decisions.csv, summary.json and scene.json
/// in the formats of `maneuvermap run` (docs/outputs.md, docs/commonroad.md), so that `maneuvermap
/// plot` draws them, and rooms.csv: each step's room (`commonroad::room`); the folder is created if
/// missing and the files overwritten.
///
/// First every file is read and its road users found (`road_users_to_measure`; with
/// `settings.on_lanelets` its lanelets made a drivable area), and every file that cannot be
/// measured is reported at once, before anything is measured: an input_error with one line per such
/// file, naming it. Then the road users of all files are measured by one pool of `settings.jobs`
/// threads, file after file: a file is read again when its first road user is taken, and its
/// outputs are written and it is released when its last one is done. The files written are a
/// function of the recordings and the settings alone, whatever `settings.jobs`. Throws
/// std::runtime_error when a file cannot be written.
std::vector<measured_file> measure_files(std::span<const measure_request> requests, const measure_settings& settings);

/// One line per measured road user: its steps, its least room (max(MI−, MI+) at τ̄) and when, the
/// steps at which the planner would not have kept to what it did, and its earliest TTC.
std::string measurement_table(const measured_file& file);

/// measurements.csv of several measured files: the header
/// `file,agent,steps,least_room,least_room_time_s,unsafe_steps,earliest_ttc_s,earliest_ttc_time_s`,
/// then one row per measured road user, the files in the order given and each one's road users in
/// the order measured; the values of each file's summary.json (the TTC columns empty when the road
/// user was never on a collision course).
std::string measurements_csv(std::span<const measured_file> files);

}  // namespace mm::cli
