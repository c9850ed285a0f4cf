#pragma once

#include <filesystem>
#include <string>

#include "mm/commonroad/scenario.hpp"

namespace mm::commonroad {

/// The CommonRoad XML file, version 2020a, that `read_scenario_text` reads as `s` again, every number
/// bit for bit (but `version`, which becomes "2020a"): the root's `benchmarkID` and `timeStepSize`,
/// each lanelet's two bounds, each obstacle as a `dynamicObstacle` (its initial state and its
/// trajectory) or a `staticObstacle` with its type and shape (a rectangle, a circle, or a polygon in
/// its own frame), and each planning problem's initial state. What `scenario` does not hold is not
/// written: no lanelet links, markings or types, no traffic rules, no `date`, `author` "maneuvermap";
/// each planning problem's goal is the time from its start to the last recorded step, the goal of
/// "stay collision-free until then" (the reader ignores goals). Numbers are written in the shortest
/// decimal form that reads back as the same double.
///
/// Throws `std::invalid_argument` when `s` does not read back as itself (an id of 0, fewer than two
/// points in a bound, states at steps that are not consecutive, a shape the reader refuses, a
/// non-finite number), naming the element.
std::string scenario_xml(const scenario& s);

/// Writes `scenario_xml(s)` to `file`. Throws as `scenario_xml` does, and
/// `std::filesystem::filesystem_error` when the file cannot be written.
void write_scenario(const scenario& s, const std::filesystem::path& file);

}  // namespace mm::commonroad
