#include "mm/sim/roundabout.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mm::sim {
namespace {

constexpr double pi = std::numbers::pi;

void check(const roundabout& ring) {
  if (!(std::isfinite(ring.radius) && ring.radius > 0.0) ||
      !(std::isfinite(ring.connection_radius) && ring.connection_radius > 0.0) ||
      !std::isfinite(ring.center.x) || !std::isfinite(ring.center.y)) {
    throw std::invalid_argument("roundabout: radius and connection_radius must be positive and finite, center finite");
  }
}

void check(const roundabout& ring, const roundabout_arm& arm) {
  check(ring);
  if (!std::isfinite(arm.angle) || !(arm.lane_offset >= 0.0 && arm.lane_offset < ring.radius) ||
      !(std::isfinite(arm.straight_length) && arm.straight_length > 0.0)) {
    throw std::invalid_argument("roundabout arm: angle finite, 0 ≤ lane_offset = " + std::to_string(arm.lane_offset) +
                                " < radius, straight_length = " + std::to_string(arm.straight_length) +
                                " > 0 expected");
  }
}

/// μ: distance along the arm's axis of the connecting arc's centre (see the header).
double axial_offset(const roundabout& ring, const roundabout_arm& arm) {
  const double outer = ring.radius + ring.connection_radius;
  const double side = arm.lane_offset + ring.connection_radius;
  return std::sqrt(outer * outer - side * side);
}

/// δ = atan2(o + r, μ).
double junction_angle(const roundabout& ring, const roundabout_arm& arm) {
  return std::atan2(arm.lane_offset + ring.connection_radius, axial_offset(ring, arm));
}

void check_laps(int extra_laps) {
  if (extra_laps < 0) throw std::invalid_argument("roundabout: extra_laps = " + std::to_string(extra_laps) + ": expected ≥ 0");
}

/// Counter-clockwise angle from `from` to `to` [rad], in (0, 2π].
double ccw_angle(double from, double to) {
  double d = std::fmod(to - from, 2.0 * pi);
  if (d <= 1e-12) d += 2.0 * pi;
  return d;
}

/// The entry's straight and connecting arc, ending on the ring at the merge angle.
path entry_piece(const roundabout& ring, const roundabout_arm& entry) {
  const double mu = axial_offset(ring, entry);
  const vec2 axis = unit_vector(entry.angle);
  const vec2 tangent_point = ring.center + entry.lane_offset * unit_vector(entry.angle + pi / 2.0) + mu * axis;
  path result(mm::pose{tangent_point + entry.straight_length * axis, entry.angle + pi});
  result.straight(entry.straight_length);
  result.turn(ring.connection_radius, -(pi / 2.0 - junction_angle(ring, entry)));
  return result;
}

/// Appends the connecting arc and straight of `exit` to a path that ends on the ring at its
/// diverge angle, heading counter-clockwise.
void append_exit(path& route, const roundabout& ring, const roundabout_arm& exit) {
  route.turn(ring.connection_radius, -(pi / 2.0 - junction_angle(ring, exit)));
  route.straight(exit.straight_length);
}

}  // namespace

double merge_angle(const roundabout& ring, const roundabout_arm& entry) {
  check(ring, entry);
  return entry.angle + junction_angle(ring, entry);
}

double diverge_angle(const roundabout& ring, const roundabout_arm& exit) {
  check(ring, exit);
  return exit.angle - junction_angle(ring, exit);
}

vec2 ring_point(const roundabout& ring, double angle) { return ring.center + ring.radius * unit_vector(angle); }

path roundabout_route(const roundabout& ring, const roundabout_arm& entry, const roundabout_arm& exit,
                      int extra_laps) {
  check_laps(extra_laps);
  const double sweep = ccw_angle(merge_angle(ring, entry), diverge_angle(ring, exit)) + 2.0 * pi * extra_laps;
  path route = entry_piece(ring, entry);
  route.turn(ring.radius, sweep);
  append_exit(route, ring, exit);
  return route;
}

path roundabout_exit_route(const roundabout& ring, double start_angle, const roundabout_arm& exit, int extra_laps) {
  check_laps(extra_laps);
  const double sweep = ccw_angle(start_angle, diverge_angle(ring, exit)) + 2.0 * pi * extra_laps;
  path route = roundabout_ring(ring, start_angle, sweep);
  append_exit(route, ring, exit);
  return route;
}

path roundabout_entry_route(const roundabout& ring, const roundabout_arm& entry, double sweep) {
  check(ring, entry);
  if (!(std::isfinite(sweep) && sweep > 0.0)) {
    throw std::invalid_argument("roundabout: sweep = " + std::to_string(sweep) + ": expected a positive angle");
  }
  path route = entry_piece(ring, entry);
  route.turn(ring.radius, sweep);
  return route;
}

path roundabout_ring(const roundabout& ring, double start_angle, double sweep) {
  check(ring);
  if (!(std::isfinite(sweep) && sweep > 0.0)) {
    throw std::invalid_argument("roundabout: sweep = " + std::to_string(sweep) + ": expected a positive angle");
  }
  return path::circular_arc(ring.center, ring.radius, start_angle, sweep);
}

}  // namespace mm::sim
