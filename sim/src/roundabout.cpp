#include "mm/sim/roundabout.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/number_text.hpp"

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
    throw std::invalid_argument("roundabout arm: angle finite, 0 ≤ lane_offset = " + number_text(arm.lane_offset) +
                                " < radius, straight_length = " + number_text(arm.straight_length) +
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

/// Most chords of one arc of a lane: a ring of radius 2e7 m (the paths' bound) takes 44,429.
constexpr double largest_lane_chords = 1e6;

/// One chord of a lane: the cross-sections at its two ends, each a centre point and half the lane's
/// width along the left normal there.
struct lane_chord {
  vec2 a, na, b, nb;
};

/// The lane `width` wide about `centre` as chords between cross-sections perpendicular to it: one
/// per straight, and for an arc as many as keep each within `roundabout_lane_chord_error` of the
/// outer edge's circle.
std::vector<lane_chord> lane_chords(const path& centre, double width) {
  const double half = 0.5 * width;
  const auto cross_section = [&](double s) {
    const path_point p = centre.at(s);
    return std::pair{p.position, half * unit_vector(p.heading + pi / 2.0)};
  };
  std::vector<lane_chord> chords_of_lane;
  for (const path_segment& piece : centre.segments()) {
    std::size_t chords = 1;
    if (piece.curvature != 0.0) {
      // A chord over the angle Δ lies (ρ + w/2)(1 − cos(Δ/2)) inside the outer edge's circle.
      const double outer = 1.0 / std::abs(piece.curvature) + half;
      const double largest_angle = 2.0 * std::acos(1.0 - roundabout_lane_chord_error / outer);
      const double needed = std::ceil(std::abs(piece.curvature) * piece.length / largest_angle);
      if (!(needed <= largest_lane_chords)) {  // also NaN, and inf where the radius makes the angle 0
        throw std::invalid_argument("roundabout: an arc of radius " + number_text(outer - half) + " m over " +
                                    number_text(piece.length) + " m needs " + number_text(needed) +
                                    " chords within " + number_text(roundabout_lane_chord_error) +
                                    " m of its edge: expected at most " + number_text(largest_lane_chords));
      }
      chords = std::max<std::size_t>(static_cast<std::size_t>(needed), 1);
    }
    for (std::size_t i = 0; i < chords; ++i) {
      const double from = piece.start_arc_length + piece.length * static_cast<double>(i) / static_cast<double>(chords);
      const double to = piece.start_arc_length + piece.length * static_cast<double>(i + 1) / static_cast<double>(chords);
      const auto [a, na] = cross_section(from);
      const auto [b, nb] = cross_section(to);
      chords_of_lane.push_back({a, na, b, nb});
    }
  }
  return chords_of_lane;
}

/// Appends to `outline` the lane of `chords`: a quadrilateral {a − n, b − n, b + n, a + n} per
/// chord; the first one's start edge (3) is open when `open_start`, the last one's end edge (1)
/// when `open_end`.
void add_lane(mm::drivable_outline& outline, const std::vector<lane_chord>& chords, bool open_start, bool open_end) {
  const std::size_t first = outline.polygons.size();
  for (const lane_chord& c : chords) outline.polygons.push_back({c.a - c.na, c.b - c.nb, c.b + c.nb, c.a + c.na});
  if (open_start) outline.open_edges.push_back({first, 3});
  if (open_end) outline.open_edges.push_back({outline.polygons.size() - 1, 1});
}

/// The edges of a lane's chords: the first one's start cross-section, then each one's end.
lane_edges edges_of(const std::vector<lane_chord>& chords) {
  lane_edges edges;
  edges.left.push_back(chords.front().a + chords.front().na);
  edges.right.push_back(chords.front().a - chords.front().na);
  for (const lane_chord& c : chords) {
    edges.left.push_back(c.b + c.nb);
    edges.right.push_back(c.b - c.nb);
  }
  return edges;
}

/// The connecting arc and straight of `exit`, from the ring at its diverge angle.
path exit_piece(const roundabout& ring, const roundabout_arm& exit) {
  const double angle = diverge_angle(ring, exit);
  path result(mm::pose{ring_point(ring, angle), angle + pi / 2.0});
  append_exit(result, ring, exit);
  return result;
}

/// Throws unless the ring and arms are valid and 0 < `lane_width` < `widest_lane(ring)`.
void check_lane_width(const roundabout& ring, std::span<const roundabout_arm> arms, double lane_width) {
  check(ring);
  for (const roundabout_arm& arm : arms) check(ring, arm);
  if (!(std::isfinite(lane_width) && lane_width > 0.0 && lane_width < widest_lane(ring))) {
    throw std::invalid_argument("roundabout: lane width = " + number_text(lane_width) +
                                ": expected above 0 and below twice the smaller of radius and connection_radius (" +
                                number_text(widest_lane(ring)) + ")");
  }
}

}  // namespace

double widest_lane(const roundabout& ring) { return 2.0 * std::min(ring.radius, ring.connection_radius); }

mm::drivable_outline roundabout_lanes(const roundabout& ring, std::span<const roundabout_arm> arms, double lane_width) {
  check_lane_width(ring, arms, lane_width);
  mm::drivable_outline outline;
  add_lane(outline, lane_chords(path::circular_arc(ring.center, ring.radius, 0.0, 2.0 * pi), lane_width), false, false);
  for (const roundabout_arm& arm : arms) {
    add_lane(outline, lane_chords(entry_piece(ring, arm), lane_width), true, false);
    add_lane(outline, lane_chords(exit_piece(ring, arm), lane_width), false, true);
  }
  return outline;
}

std::vector<lane_edges> roundabout_lane_edges(const roundabout& ring, std::span<const roundabout_arm> arms,
                                              double lane_width) {
  check_lane_width(ring, arms, lane_width);
  // The ring's pieces run between consecutive junctions (merge and diverge angles, in [0, 2π)).
  std::vector<double> junctions;
  const auto in_turn = [](double angle) {
    const double a = std::fmod(angle, 2.0 * pi);
    return a < 0.0 ? a + 2.0 * pi : a;
  };
  for (const roundabout_arm& arm : arms) {
    junctions.push_back(in_turn(merge_angle(ring, arm)));
    junctions.push_back(in_turn(diverge_angle(ring, arm)));
  }
  if (junctions.empty()) junctions = {0.0, pi / 2.0, pi, 3.0 * pi / 2.0};
  std::sort(junctions.begin(), junctions.end());
  constexpr double same_angle = 1e-9;  // [rad]: junctions closer than this are one
  junctions.erase(std::unique(junctions.begin(), junctions.end(),
                              [](double a, double b) { return b - a <= same_angle; }),
                  junctions.end());
  if (junctions.size() > 1 && junctions.front() + 2.0 * pi - junctions.back() <= same_angle) junctions.pop_back();
  const std::size_t pieces = junctions.size();
  const auto piece_at = [&](double angle) {  // the piece that starts at the junction nearest `angle`
    std::size_t best = 0;
    double nearest = 2.0 * pi;
    for (std::size_t k = 0; k < pieces; ++k) {
      const double d = std::abs(std::remainder(angle - junctions[k], 2.0 * pi));
      if (d < nearest) {
        nearest = d;
        best = k;
      }
    }
    return best;
  };
  std::vector<lane_edges> lanes;
  for (std::size_t k = 0; k < pieces; ++k) {
    const double sweep = (k + 1 < pieces ? junctions[k + 1] : junctions.front() + 2.0 * pi) - junctions[k];
    const std::vector<lane_chord> arc = lane_chords(path::circular_arc(ring.center, ring.radius, junctions[k], sweep), lane_width);
    lanes.push_back(edges_of(arc));
    lanes.back().successors.push_back((k + 1) % pieces);
  }
  for (const roundabout_arm& arm : arms) {
    const std::vector<lane_chord> entry = lane_chords(entry_piece(ring, arm), lane_width);
    const std::vector<lane_chord> exit = lane_chords(exit_piece(ring, arm), lane_width);
    lanes.push_back(edges_of(entry));
    lanes.back().successors.push_back(piece_at(merge_angle(ring, arm)));
    const std::size_t exit_index = lanes.size();
    lanes.push_back(edges_of(exit));
    const std::size_t before_exit = (piece_at(diverge_angle(ring, arm)) + pieces - 1) % pieces;
    lanes[before_exit].successors.push_back(exit_index);
  }
  return lanes;
}

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
    throw std::invalid_argument("roundabout: sweep = " + number_text(sweep) + ": expected a positive angle");
  }
  path route = entry_piece(ring, entry);
  route.turn(ring.radius, sweep);
  return route;
}

path roundabout_ring(const roundabout& ring, double start_angle, double sweep) {
  check(ring);
  if (!(std::isfinite(sweep) && sweep > 0.0)) {
    throw std::invalid_argument("roundabout: sweep = " + number_text(sweep) + ": expected a positive angle");
  }
  return path::circular_arc(ring.center, ring.radius, start_angle, sweep);
}

}  // namespace mm::sim
