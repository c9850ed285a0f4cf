#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm {

/// A straight piece of a line, from `a` to `b` [m].
struct segment {
  vec2 a;
  vec2 b;
};

/// A segment with its line, for `line_distance_bound` and the distances that ask a segment many
/// times: its ends, its unit direction (zero for a point segment, which has no line) and its length
/// [m], computed once.
struct segment_line {
  vec2 a;
  vec2 b;
  vec2 direction;
  double length = 0.0;
  explicit segment_line(const segment& s);
  segment segment_of() const { return {a, b}; }
};

/// Edge `edge` of polygon `polygon`: from its vertex `edge` to the next (the last to the first).
struct polygon_edge {
  std::size_t polygon = 0;
  std::size_t edge = 0;
  friend bool operator==(const polygon_edge&, const polygon_edge&) = default;
};

/// What a drivable area is made of, as a value: its polygons [m] and the edges of theirs that lead
/// on beyond the map (see `drivable_area`). No polygon: no drivable area.
struct drivable_outline {
  std::vector<std::vector<vec2>> polygons;
  std::vector<polygon_edge> open_edges;
  bool empty() const { return polygons.empty(); }

  friend bool operator==(const drivable_outline&, const drivable_outline&) = default;
};

/// Gaps in a drivable area narrower than this are closed [m]: two polygons whose edges
/// lie closer than it are one road there. Recorded road networks need it: the shared bound of two
/// neighbouring lanelets is often sampled at different points by each, a centimetre or two apart
/// (1.3 cm in USA_US101-4 of the bundled data), which a smaller closing would turn into a boundary
/// down the middle of the road.
inline constexpr double drivable_area_closing = 0.1;

/// Largest |coordinate| of a drivable area's vertex [m]: road networks of a few hundred kilometres,
/// with the closing distance (`drivable_area_closing`) far above the doubles' rounding there.
inline constexpr double largest_drivable_coordinate = 1e7;

/// Most vertices a drivable area may have in all: the boundary is found by testing each edge against
/// the edges whose extents along x overlap its own, which is near-linear for road networks but
/// quadratic in the worst case (every edge across every other), so the count is bounded.
inline constexpr std::size_t largest_drivable_vertex_count = 100000;

/// Why `polygons` cannot be a drivable area, naming the polygon and vertex (`polygons[i]`,
/// `polygons[i][j]`): none given, more than `largest_drivable_vertex_count` vertices in all, fewer
/// than 3 in a polygon, a coordinate that is not finite or larger than
/// `largest_drivable_coordinate`, or no area (all vertices on one line); or an open edge
/// (`open_edges[k]`) that is not an edge of a polygon — or nothing.
std::optional<std::string> drivable_area_error(const std::vector<std::vector<vec2>>& polygons,
                                               const std::vector<polygon_edge>& open_edges = {});

/// The drivable area of spec §5: the union of simple polygons in the world frame [m] (either
/// orientation; a self-intersecting polygon counts by the even-odd rule), and the boundary of that
/// union as segments, computed once: the parts of the polygons' edges with the union on one side and
/// not on the other (`drivable_area_closing` from the edge). Edges shared by neighbouring polygons,
/// and the parts of an edge inside another polygon (more than 1 µm from its edges, however near),
/// are not boundary: lanelets that overlap at an intersection or share a bound make one road, and
/// lanes that meet tangentially (a roundabout's entry joining the ring) are bounded by their outer
/// edges only. Edges marked *open* are never boundary: where a
/// road leads on beyond what is mapped (the ends of a recording's lanelets, of a scenario's roads),
/// a maneuver that drives through the end has not left the road.
///
/// A footprint that starts inside the area leaves it exactly when it touches the boundary, which is
/// what the planner tests (docs/method.md §5).
class drivable_area {
 public:
  /// Throws std::invalid_argument with `drivable_area_error`'s message when there is one.
  explicit drivable_area(std::vector<std::vector<vec2>> polygons, const std::vector<polygon_edge>& open_edges = {});
  explicit drivable_area(const drivable_outline& outline) : drivable_area(outline.polygons, outline.open_edges) {}

  const std::vector<std::vector<vec2>>& polygons() const { return polygons_; }
  const std::vector<polygon_edge>& open_edges() const { return open_edges_; }
  const std::vector<segment>& boundary() const { return boundary_; }
  /// The boundary's segments with their lines (`segment_line`), in the same order: what the distance
  /// tests that ask every segment many times take, computed once.
  const std::vector<segment_line>& boundary_lines() const { return boundary_lines_; }

  /// True when `p` lies in one of the polygons (even-odd rule; on an edge counts as either).
  bool contains(vec2 p) const;

 private:
  struct box {
    vec2 lo;
    vec2 hi;
  };
  std::vector<std::vector<vec2>> polygons_;
  std::vector<polygon_edge> open_edges_;
  std::vector<box> boxes_;
  std::vector<segment> boundary_;
  std::vector<segment_line> boundary_lines_;
};

/// Signed distance [m] of a placed footprint to a segment: the gap when apart, minus the
/// penetration depth (the shortest translation that separates them) when the segment cuts the
/// footprint's core; the footprint's radius subtracted. Continuous, and no more than d apart for two
/// placements whose points are no more than d apart.
double signed_distance(const placed_footprint& f, const segment& s);
/// `signed_distance(f, line.segment_of())` bit for bit, without computing the line again.
double signed_distance(const placed_footprint& f, const segment_line& line);

/// A lower bound of `signed_distance(f, s)` [m], cheap and tight for a road's edge beside a car:
/// for a rectangle, its signed distance to the segment's line, |n·(c − a)| − h_n − radius, with n
/// the line's normal and h_n = l|n·x| + w|n·y| the rectangle's half extent along it (the gap to a
/// segment is no smaller than to its line, and a segment cuts no deeper than its line); −∞ for
/// other footprints and point segments. Within rounding: compare with a slack.
double line_distance_bound(const placed_footprint& f, const segment_line& line);

/// The reference for `signed_distance` of a footprint and a segment, which takes a rectangle in its
/// own frame: the footprints' general `signed_distance`, the segment a core of two vertices.
double signed_distance_reference(const placed_footprint& f, const segment& s);

/// Smallest signed distance of the footprint to the segments [m], `cap` when every segment is
/// farther than it: positive when the footprint is clear of them (and cap > 0), ≤ 0 when it touches
/// or crosses one. min(cap, min over the segments of `signed_distance`), exactly: segments that
/// cannot lower it are not asked.
double boundary_clearance(std::span<const segment> boundary, const placed_footprint& f, double cap);
/// `boundary_clearance` of the segments of `boundary` bit for bit, their lines computed before
/// (`drivable_area::boundary_lines`).
double boundary_clearance(std::span<const segment_line> boundary, const placed_footprint& f, double cap);

}  // namespace mm
