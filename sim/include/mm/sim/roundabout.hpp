#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "mm/drivable_area.hpp"
#include "mm/geometry.hpp"
#include "mm/sim/path.hpp"

namespace mm::sim {

/// A one-lane roundabout with right-hand traffic: vehicles circulate counter-clockwise on the
/// circulating lane's centre line, the ring of radius R about `center`.
///
/// Geometry of an arm (see docs/simulator.md): the arm's axis is the ray from the centre at polar
/// angle φ. Its lane centre line is parallel to the axis, `lane_offset` = o to the right of the
/// direction of travel (inbound for an entry, outbound for an exit). The lane joins the ring
/// through a connecting arc of radius r, tangent to the lane and externally tangent to the ring,
/// turning right. Its centre F lies at distance R + r from the centre and r from the lane line:
///
///     F = C + (o + r)·n + μ·e_φ,   μ = √((R + r)² − (o + r)²),   e_φ = (cos φ, sin φ),
///
/// with n = e_{φ+π/2} for an entry and n = e_{φ−π/2} for an exit. The arc touches the ring at the
/// merge angle ψ = φ + δ (entry) or the diverge angle ψ = φ − δ (exit), δ = atan2(o + r, μ), and
/// turns by −(π/2 − δ). Every route built here is tangent-continuous (straight, arc, ring, arc,
/// straight), so a pure-pursuit follower tracks it without heading jumps.
struct roundabout {
  vec2 center;                     ///< C [m]
  double radius = 25.0;            ///< R: radius of the circulating lane's centre line [m], > lane offsets
  double connection_radius = 20.0; ///< r: radius of the arcs joining the arms to the ring [m], > 0
};

/// One entry or exit lane of a roundabout.
struct roundabout_arm {
  double angle = 0.0;            ///< φ: polar angle of the arm's axis about the centre [rad], CCW from +x
  double lane_offset = 0.0;      ///< o: lane centre line to the right of travel from the axis [m], 0 ≤ o < R
  double straight_length = 50.0; ///< length of the straight lane outside the connecting arc [m], > 0
};

/// Polar angle ψ [rad] at which an entry's connecting arc merges into the ring: φ + δ.
double merge_angle(const roundabout& ring, const roundabout_arm& entry);

/// Polar angle ψ [rad] at which an exit's connecting arc leaves the ring: φ − δ.
double diverge_angle(const roundabout& ring, const roundabout_arm& exit);

/// The point of the ring at polar angle `angle` [rad]: C + R·e_angle.
vec2 ring_point(const roundabout& ring, double angle);

/// In along `entry`, counter-clockwise around the ring from its merge angle to the diverge angle
/// of `exit` (the CCW angle between them, in (0, 2π]; plus `extra_laps` full laps), out along
/// `exit`. Starts `entry.straight_length` before the connecting arc; length
/// ≈ both straights + both arcs + R·(swept angle).
path roundabout_route(const roundabout& ring, const roundabout_arm& entry, const roundabout_arm& exit,
                      int extra_laps = 0);

/// Starts on the ring at polar angle `start_angle` [rad], circulates counter-clockwise to the
/// diverge angle of `exit` (CCW angle in (0, 2π], plus `extra_laps`) and leaves along `exit`.
/// Arc length on the ring before the connecting arc: R·(swept angle).
path roundabout_exit_route(const roundabout& ring, double start_angle, const roundabout_arm& exit,
                           int extra_laps = 0);

/// Enters along `entry` and then circulates counter-clockwise for `sweep` [rad] > 0 on the ring.
path roundabout_entry_route(const roundabout& ring, const roundabout_arm& entry, double sweep);

/// The ring alone from polar angle `start_angle` [rad], counter-clockwise over `sweep` [rad] > 0.
path roundabout_ring(const roundabout& ring, double start_angle, double sweep);

/// Largest distance [m] between a lane's curved edge and the chords `roundabout_lanes` draws it
/// with: half `mm::drivable_area_closing`, and few pieces (the outer edge of a 3.5 m lane on a 25 m
/// ring in 52 chords), since the road constraint's cost grows with the segments near the ego (at
/// 1 cm a plan of S2 on its lanes took about twice as long; docs/method.md §5 item 16).
inline constexpr double roundabout_lane_chord_error = 0.05;

/// The bound a lane's width [m] must stay below for `roundabout_lanes`: 2·min(R, r), beyond which
/// the inner edge of the ring or of a connecting arc would turn inside out.
double widest_lane(const roundabout& ring);

/// The lanes of a roundabout as a drivable area (spec §5's road constraint, docs/method.md §5
/// item 16): the circulating lane, the annulus R ± w/2 about C, and for every arm its entry lane and
/// its exit lane (their straights and connecting arcs), each w = `lane_width` [m] wide about its
/// centre line. An arc is drawn with chords between cross-sections perpendicular to it, each chord
/// within `roundabout_lane_chord_error` of the circle it cuts (the outer side of a bend lies up to
/// that much inside the true edge, the inner side outside it). The outer end of each straight
/// leads on (an open edge: a vehicle may drive off the drawn arm). With w = 2o (o the arm's lane
/// offset) an arm's two lanes meet along its axis.
///
/// Throws std::invalid_argument unless 0 < w < `widest_lane(ring)` and every arm is valid (as
/// `merge_angle`), or when an arc would need more than a million chords (a ring of radius above 1e10 m).
mm::drivable_outline roundabout_lanes(const roundabout& ring, std::span<const roundabout_arm> arms, double lane_width);

/// A lane's two edges, each a polyline in the direction of travel [m]: `left` on the left of it.
struct lane_edges {
  std::vector<vec2> left;
  std::vector<vec2> right;
  std::vector<std::size_t> successors;  ///< the lanes that continue it: indices into the same list
};

/// The lanes of `roundabout_lanes` as a lane network, e.g. for CommonRoad lanelets (left and right
/// bound, successors): first the circulating lane in pieces between consecutive junctions (the
/// merge and diverge angles, counter-clockwise from the smallest in [0, 2π); four quarters from 0
/// without arms), each followed by the next and, where an exit diverges at its end, by that exit;
/// then for every arm its entry lane, followed by the piece that starts at its merge angle, and its
/// exit lane. Each lane is drawn as `roundabout_lanes` draws it, in chords between cross-sections
/// perpendicular to its centre line within `roundabout_lane_chord_error` of its edges (the arms'
/// lanes with the same cross-sections; the ring's pieces each with their own). Throws as
/// `roundabout_lanes`.
std::vector<lane_edges> roundabout_lane_edges(const roundabout& ring, std::span<const roundabout_arm> arms,
                                              double lane_width);

}  // namespace mm::sim
