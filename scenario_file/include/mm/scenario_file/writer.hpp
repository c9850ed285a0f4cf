#pragma once

#include <filesystem>
#include <string>

#include "mm/scenario_file/loader.hpp"
#include "mm/sim/scenario.hpp"

namespace mm::scenario_file {

/// The scenario file (`maneuvermap-scenario/1`, docs/scenario-format.md) that `load_text` maps
/// onto `s` exactly: `load_text(scenario_text(s), ...).scenario == s`, every number bit for bit.
///
/// The file states the scenario as the simulator runs it: every field of every agent written out
/// (no `defaults:`, no `parameters:`), SI units (`_mps`, `_rad`), start times as resolved (no
/// `meet:`), paths as a start pose and their segments (`straight_m`, `curve`, `line_to_m`: a
/// roundabout route or an arc written as the pieces it was built of), and the drivable area as its
/// polygons with their open edges. Numbers are written in the shortest decimal form that reads
/// back as the same double.
///
/// Throws `std::invalid_argument` when `s` is not a valid scenario (`mm::sim::validation_error`:
/// the file would not load) or holds a value no scenario file can state
/// (`planner.record_samples`, which is the drawing tools' business, not a scenario's).
std::string scenario_text(const mm::sim::scenario& s);

/// As `scenario_text(loaded.scenario)`, with the roundabout and the roads the file declared
/// (`roundabout:`, `roads:`), which the figures draw and the run does not use: a run of the written
/// file writes the same files as a run of `loaded`, but for the parameters and meetings its summary
/// lists (the written file has none left to resolve).
std::string scenario_text(const loaded_scenario& loaded);

/// Writes `scenario_text(s)` to `file` (replacing it). Throws `std::invalid_argument` as
/// `scenario_text` does, and `std::filesystem::filesystem_error` (the file and the reason) when it
/// cannot be written.
void write_file(const mm::sim::scenario& s, const std::filesystem::path& file);

/// Writes `scenario_text(loaded)` to `file`, as the other `write_file`.
void write_file(const loaded_scenario& loaded, const std::filesystem::path& file);

}  // namespace mm::scenario_file
