#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "mm/geometry.hpp"

namespace mm::sim {

/// One piece of a path: a straight line (κ = 0) or a circular arc of constant curvature κ,
/// starting at `start` and running `length` metres in the direction of `start.heading`.
/// The point at local arc length σ ∈ [0, length] is `to_world(start, arc_point(κ, σ))` and its
/// heading is `start.heading + κσ` (spec §3's arc, the same formula the planner uses).
struct path_segment {
  mm::pose start;                 ///< first point [m] and heading there [rad]
  double length = 0.0;            ///< [m], > 0
  double curvature = 0.0;         ///< κ [1/m], positive turning left (counter-clockwise)
  double start_arc_length = 0.0;  ///< arc length of the path at `start` [m]

  friend bool operator==(const path_segment&, const path_segment&) = default;
};

/// The geometry of a path at one arc length.
struct path_point {
  vec2 position;          ///< [m]
  double heading = 0.0;   ///< tangent direction [rad], wrapped to (−π, π]
  double curvature = 0.0; ///< κ [1/m], left positive; 0 on the straight extensions beyond the ends
};

/// A point expressed in path coordinates.
struct path_projection {
  double arc_length = 0.0;      ///< s of the nearest path point [m]; < 0 or > length() on the extensions
  /// Signed distance to the nearest path point [m]: positive when the point lies to the left of
  /// the tangent there (left of the direction of travel), negative to the right.
  double lateral_offset = 0.0;
  double distance = 0.0;        ///< |lateral_offset| [m]
  path_point nearest;           ///< the path point at `arc_length`
};

/// A planar path made of straight lines and circular arcs, parametrised by arc length s ∈ [0, L].
///
/// Beyond its ends the path is taken to continue straight along its end tangents: `at(s)` accepts
/// any s, and `project` may answer s < 0 or s > L. A polyline has heading jumps at its corners; a
/// path built with `straight` and `turn` is tangent-continuous (G¹), which is what a pure-pursuit
/// follower needs to track it without transients.
///
/// Construction throws `std::invalid_argument` on non-finite or non-positive lengths and radii.
/// Value type; every const member function is thread-safe.
class path {
 public:
  /// The empty path (no segments, length 0): the value of an unset field; not drivable.
  path() = default;

  /// An empty path whose first segment will start at `start`.
  explicit path(const mm::pose& start);

  /// The polyline through `points` (at least 2, consecutive points distinct): straight segments
  /// with heading jumps at the inner vertices.
  static path polyline(std::span<const vec2> points);

  /// The arc of the circle of `radius` [m] about `center` from polar angle `start_angle` [rad]
  /// over `sweep` [rad] (positive counter-clockwise, |sweep| ≤ 2π·k allowed): length R·|sweep|.
  static path circular_arc(vec2 center, double radius, double start_angle, double sweep);

  /// Appends a straight segment of `length` [m] > 0 along the current end heading.
  path& straight(double length);

  /// Appends a circular arc of `radius` [m] > 0 turning by `angle` [rad] (positive = left,
  /// counter-clockwise; |angle| may exceed 2π), tangent to the current end: length R·|angle|.
  path& turn(double radius, double angle);

  /// Appends a straight segment from the current end to `point` (≠ the end): a corner unless
  /// `point` lies straight ahead.
  path& line_to(vec2 point);

  /// Appends a segment of constant `curvature` κ [1/m] (positive = left; 0: straight) and `length`
  /// [m] > 0, tangent to the current end: what `turn(1/|κ|, ±κ·length)` and `straight(length)` add,
  /// given by the two numbers a segment stores, so that a written path reads back bit for bit.
  path& curve(double length, double curvature);

  /// Equal segments and end: the same path, bit for bit.
  friend bool operator==(const path&, const path&) = default;

  bool empty() const { return segments_.empty(); }
  /// L [m].
  double length() const;
  std::span<const path_segment> segments() const { return segments_; }
  /// Where the next appended segment starts: the end point and heading of the path.
  mm::pose end_pose() const { return end_; }

  /// Position, heading and curvature at arc length `s` [m]. On a segment boundary the later
  /// segment's curvature applies. For s < 0 or s > L: the straight extension. Requires !empty().
  path_point at(double arc_length) const;

  /// The nearest point of the path, extensions included, to `point` (global search).
  /// Requires !empty(). Ties go to the smallest s.
  path_projection project(vec2 point) const;

  /// The nearest point to `point` among arc lengths within [hint − window, hint + window] [m]:
  /// keeps a follower on the same branch when the path passes near itself (a U-turn, a lap of a
  /// roundabout). `window` > 0. Requires !empty().
  path_projection project(vec2 point, double hint, double window) const;

 private:
  path_projection project_within(vec2 point, double lo, double hi) const;
  std::size_t segment_index(double arc_length) const;

  std::vector<path_segment> segments_;
  mm::pose end_;
};

/// One operation that appends to a path: `curve(length, curvature)`, `straight(length)` or
/// `line_to(point)`.
struct path_step {
  enum class kind : std::uint8_t { curve, straight, line_to };
  kind operation = kind::straight;
  double length = 0.0;     ///< [m] > 0, of `curve` and `straight`
  double curvature = 0.0;  ///< κ [1/m], of `curve`
  vec2 point;              ///< [m], of `line_to`

  friend bool operator==(const path_step&, const path_step&) = default;
};

/// A path as the start pose and the operations that build it: `path(start)`, then each step.
struct path_steps {
  mm::pose start;
  std::vector<path_step> steps;

  friend bool operator==(const path_steps&, const path_steps&) = default;
};

/// The steps that rebuild `p` bit for bit (`path_of(steps_of(p)) == p`): `curve` for an arc,
/// `straight` for a straight segment that continues the end pose, `line_to` for one that turns a
/// corner (a polyline's). What the scenario writer writes and a pickled path holds. Throws
/// `std::logic_error` should a path's segments not be rebuilt so (none built by `path`'s operations).
path_steps steps_of(const path& p);

/// `path(steps.start)` with every step appended; `std::invalid_argument` as those operations.
path path_of(const path_steps& steps);

}  // namespace mm::sim
