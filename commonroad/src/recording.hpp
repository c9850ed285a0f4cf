#pragma once

// What reading, measuring and replaying a recording share: finding a road user, its state at a
// step, the check that it can be the planner's ego, its largest speed, and the polygon a circle
// becomes (internal to mm::commonroad).

#include <cstdint>
#include <string>
#include <vector>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/scenario.hpp"
#include "mm/forecast.hpp"
#include "mm/geometry.hpp"

namespace mm::commonroad::detail {

const obstacle* find_obstacle(const scenario& s, std::uint32_t id);

bool is_pedestrian(const obstacle& o);

/// A road user the planner can take as its ego: a recorded vehicle (`measurable_road_users`).
bool can_be_measured(const obstacle& o);

/// t_k = k·Δt [s].
double step_time(const scenario& s, std::int64_t step);

/// The state of `o` at `step`, or null when it is not recorded then (states are at consecutive steps).
const state* state_at(const obstacle& o, std::int64_t step);

/// The road user `agent` as the planner's ego, or `measure_error` saying why it cannot be.
const obstacle& measured(const scenario& s, std::uint32_t agent);

/// A recorded state as an observation: its time, its pose (heading wrapped) and max(v, 0).
observation observed(const scenario& s, const state& x);

/// The largest recorded speed of `o` [m/s], at least 0.
double largest_speed(const obstacle& o);

/// The regular 16-gon around a circle of `radius` [m] about the origin, counter-clockwise from +x:
/// how a circle becomes a polygon (an offset circle in a file, a static disc in a replay).
std::vector<vec2> circle_polygon(double radius);

}  // namespace mm::commonroad::detail
