#pragma once

#include <nlohmann/json.hpp>

#include "mm/planner.hpp"

namespace mm::capture {

/// A planning input as JSON, every number written so that it reads back bit for bit: what
/// `maneuvermap_capture --save` writes and `maneuvermap_replan` plans on (docs/performance.md). A
/// drivable area is written as its polygons and open edges (`drivable_area`, absent without one).
nlohmann::json to_json(const plan_input& input);

/// The planning input `to_json` wrote. Throws nlohmann::json::exception naming a missing or
/// mistyped key, std::invalid_argument for an unknown footprint, obstacle kind or policy, or a
/// drivable area that `mm::drivable_area` refuses.
plan_input plan_input_from_json(const nlohmann::json& json);

}  // namespace mm::capture
