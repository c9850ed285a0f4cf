#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mm/drivable_area.hpp"

#include "mm/forecast_policy.hpp"
#include "mm/sim/roundabout.hpp"
#include "mm/sim/scenario.hpp"

namespace mm::scenario_file {

/// The format this loader reads: the value of the `format` key (docs/scenario-format.md).
inline constexpr std::string_view format_version = "maneuvermap-scenario/1";

/// A problem with a scenario or with the options applied to it: where it is (source, 1-based line
/// and column of the offending YAML node, 0 when unknown), the field path (`agents[0].speed_kmh`)
/// and what is wrong, usually `= VALUE: expected WHAT`. `what()` is
/// `source:line:column: field: problem`.
class scenario_error : public std::runtime_error {
 public:
  scenario_error(std::string source, int line, int column, std::string field, std::string problem);

  const std::string& source() const { return source_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string source_;
  int line_ = 0;
  int column_ = 0;
  std::string field_;
  std::string problem_;
};

/// A named number of the `parameters:` map that fields reference as `$name`.
struct parameter {
  std::string name;            ///< carries its unit, e.g. `a_kmh`
  double value = 0.0;          ///< after overrides
  double default_value = 0.0;  ///< as written in the file
};

/// A named arm of the scenario's roundabout.
struct named_arm {
  std::string name;
  mm::sim::roundabout_arm arm;
};

/// The roundabout a scenario declares (paths refer to its arms by name).
struct roundabout_geometry {
  mm::sim::roundabout ring;
  std::vector<named_arm> arms;  ///< in file order
  /// The width of its lanes in the drivable area [m] (`drivable_area: {roundabout: ...}`), if the
  /// scenario makes one of them.
  std::optional<double> lane_width;
};

/// The width of a roundabout's lanes [m] where a scenario gives none (`drivable_area: {roundabout:
/// true}`, `--on-roads`, the lanes of a CommonRoad recording).
inline constexpr double default_roundabout_lane_width = 3.5;

/// The arms of `g` without their names, in file order.
std::vector<mm::sim::roundabout_arm> arms_of(const roundabout_geometry& g);

/// The lanes of `g` as a lane network (`mm::sim::roundabout_lane_edges`), as a CommonRoad recording
/// writes them: as wide as the scenario's drivable area has them, else
/// `default_roundabout_lane_width`, or half the widest lane the ring can have where that is not
/// narrower. Throws as `roundabout_lane_edges`.
std::vector<mm::sim::lane_edges> lane_network(const roundabout_geometry& g);

/// A road drawn under the agents; not used by the simulation.
struct road {
  std::string name;
  std::vector<vec2> centre_line;  ///< [m]
  double width = 0.0;             ///< [m]
};

/// The area a road covers, as polygons whose union it is: a rectangle `width` wide about each piece
/// of the centre line, and at each bend, before the next piece's rectangle, the triangle that
/// closes the outer side between the two (a bevelled joint). Its two ends are open edges: the road
/// leads on beyond them. What `drivable_area: {roads: true}` makes of the file's roads.
mm::drivable_outline road_polygons(const road& r);

/// How a `meet:` entry timed two agents (travel at constant initial speed to the conflict point).
struct meeting_report {
  std::string first;
  std::string second;
  double first_distance = 0.0;   ///< from its start to the conflict point along its (timing) path [m]
  double second_distance = 0.0;  ///< [m]
  double first_travel = 0.0;     ///< [s]
  double second_travel = 0.0;    ///< [s]
  double lag = 0.0;              ///< second arrives this much after first [s]
  double first_start = 0.0;      ///< resulting start times [s]
  double second_start = 0.0;
};

/// A scenario file mapped onto the simulator's types, with what the file adds around them.
struct loaded_scenario {
  mm::sim::scenario scenario;
  std::vector<parameter> parameters;           ///< in file order
  std::optional<roundabout_geometry> roundabout;
  std::vector<road> roads;
  std::vector<meeting_report> meetings;        ///< in file order
  std::string source;                          ///< file name or `builtin:NAME`
};

/// What the command line changes in a scenario.
struct load_options {
  /// `--set NAME=VALUE`: parameter overrides, in order (a later one wins). Unknown names are errors.
  std::vector<std::pair<std::string, double>> overrides;
  /// `--policy`: replaces the forecast policy of every planning vehicle.
  std::optional<mm::forecast_policy> policy;
  /// `--seed`: replaces the scenario's seed.
  std::optional<std::uint64_t> seed;
  /// `--on-roads`: the scenario's roads and its roundabout's lanes (3.5 m) become its drivable area,
  /// as `drivable_area: {roads: true, roundabout: true}` would make them (spec §5's road constraint).
  /// An error when the scenario has neither, or gives its own `drivable_area:`.
  bool on_roads = false;
};

/// Parses and maps scenario YAML `text`; `source` names it in messages. Throws scenario_error
/// for any problem: malformed YAML, unknown keys, missing required fields, wrong types, values out
/// of range, unknown agents or parameters, impossible timing, and whatever
/// `mm::sim::validation_error` finds in the mapped scenario.
loaded_scenario load_text(std::string_view text, const std::string& source, const load_options& options = {});

/// Reads and loads the file at `file`. Throws scenario_error (also when it cannot be read).
loaded_scenario load_file(const std::filesystem::path& file, const load_options& options = {});

/// Loads a built-in scenario by name or a file: an argument containing '/' or ending in `.yaml`
/// or `.yml` is a path; otherwise a built-in name if there is one, else a path.
loaded_scenario load(std::string_view file_or_builtin, const load_options& options = {});

/// The forms of a policy value `parse_policy` reads, for messages and help texts.
inline constexpr std::string_view policy_forms = "adj, const:SECONDS or robust";

/// Parses a `--policy` value: `adj`, `const:SECONDS` (e.g. `const:1.0`) or `robust`; none if malformed.
std::optional<mm::forecast_policy> parse_policy(std::string_view text);

/// `adj`, `robust`, or `const:SECONDS` with the shortest decimal form of the forecast time (`const:0.5`).
std::string policy_name(const mm::forecast_policy& policy);

/// The closest of `candidates` to `word` when it is a plausible typo of it, else "" (the "did you
/// mean ...?" of messages; also used by the sweep files of the command line).
std::string closest_name(std::string_view word, const std::vector<std::string>& candidates);

/// What an "unknown key" message adds: "; did you mean X?" for a plausible typo of one of
/// `candidates`, else the (at most three) candidates that have every `_`-separated word of `word`
/// (`speed_kmh`: "; did you mean desired_speed_kmh or initial_speed_kmh?"), else "; expected one of "
/// and every candidate, in their order. Used by the scenario files and the sweep files.
std::string unknown_key_hint(std::string_view word, const std::vector<std::string>& candidates);

/// Parses `NAME=VALUE` of `--set`; none if malformed (no '=', empty name, VALUE not a finite number).
std::optional<std::pair<std::string, double>> parse_override(std::string_view text);

}  // namespace mm::scenario_file
