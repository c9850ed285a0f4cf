#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "mm/commonroad/scenario.hpp"

namespace mm::commonroad {

/// The `date` written for a scenario that has none (a simulated run): a fixed one, so that the same
/// scenario is always written as the same bytes.
inline constexpr std::string_view undated = "1970-01-01";

/// `s` as `read_scenario_text` reads its `scenario_xml` back: the version "2020a", the date
/// `undated` when it has none, its static obstacles before its dynamic ones (each kind in its
/// order), and a yaw rate of 0 in each planning problem's initial state that has none.
scenario as_written(scenario s);

/// The CommonRoad XML file, version 2020a, that `read_scenario_text` reads as `as_written(s)`,
/// every number bit for bit. It has what the 2020a schema requires: the root's `benchmarkID`,
/// `date` (`undated` when `s` has none), `author` "maneuvermap", `affiliation`, `source` and
/// `timeStepSize`; a `location` with CommonRoad's values for an unknown one (-999, 999, 999) and
/// empty `scenarioTags`; each lanelet's two bounds, its predecessors and successors, and a
/// `laneletType` of `unknown`; each static
/// obstacle, then each dynamic one, with its type, shape (a rectangle, a circle, or a polygon in its
/// own frame), initial state and trajectory; each planning problem's initial state with every
/// element the schema asks for (a slip angle of 0) and its goal, the time from its start to the last
/// recorded step ("stay collision-free until then"; the reader ignores goals). What `scenario` does
/// not hold is not written: no lanelet neighbours, markings or types, no traffic rules, no place or
/// tags.
/// Numbers are written in the shortest fixed-point form that reads back as the same double (the
/// schema's `xs:decimal` has no exponent).
///
/// Throws `std::invalid_argument` when `s` does not read back as itself (an id of 0, fewer than two
/// points in a bound, states at steps that are not consecutive, a shape the reader refuses, a
/// non-finite number, a date that is not YYYY-MM-DD), naming the element.
std::string scenario_xml(const scenario& s);

/// Writes `scenario_xml(s)` to `file`. Throws as `scenario_xml` does, and
/// `std::filesystem::filesystem_error` when the file cannot be written.
void write_scenario(const scenario& s, const std::filesystem::path& file);

}  // namespace mm::commonroad
