#pragma once

#include <cstdlib>
#include <cstring>
#include <vector>

#include "mm/sim/scenario.hpp"

namespace mm::sim::testing {

/// True under the sanitizer build (MM_TEST_SCALE=sanitize), where long runs are shortened.
inline bool sanitize_scale() {
  const char* scale = std::getenv("MM_TEST_SCALE");
  return scale != nullptr && std::strcmp(scale, "sanitize") == 0;
}

/// A straight path from `from` in direction `heading` [rad], `length` metres long.
inline path straight_path(vec2 from, double heading, double length) {
  path p(mm::pose{from, heading});
  p.straight(length);
  return p;
}

/// A planning vehicle driving `p` from its start at constant `speed` [m/s] (= v_des).
inline planning_vehicle cruising(const char* name, path p, double speed) {
  planning_vehicle v;
  v.name = name;
  v.path = std::move(p);
  v.initial_speed = speed;
  v.desired_speed = speed;
  return v;
}

/// A scripted vehicle driving `p` at constant `speed` [m/s].
inline scripted_vehicle scripted(const char* name, path p, double speed) {
  scripted_vehicle v;
  v.name = name;
  v.motion.path = std::move(p);
  v.motion.speed = speed_profile::constant(speed);
  return v;
}

/// The paper's Fig. 1 crossing (S1): A east along y = 0 from x = 0 at 40 km/h; B south along
/// x = 40 from y = 36 at 36 km/h. Both reach (40, 0) at t = 3.6 s if neither reacts.
inline scenario crossing(bool avoidance) {
  scenario s;
  s.name = "crossing";
  s.duration = 6.0;
  planning_vehicle a = cruising("A", straight_path({0.0, 0.0}, 0.0, 200.0), 40.0 / 3.6);
  a.avoidance = avoidance;
  s.planning_vehicles.push_back(a);
  s.scripted_vehicles.push_back(scripted("B", straight_path({40.0, 36.0}, -std::numbers::pi / 2.0, 100.0), 10.0));
  return s;
}

}  // namespace mm::sim::testing
