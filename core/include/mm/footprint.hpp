#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "mm/geometry.hpp"
#include "mm/input_bounds.hpp"

namespace mm {

/// Rectangle centred on the reference point, `length` along the heading, `width` across [m] (spec §2).
struct rectangle {
  double length = 4.5;
  double width = 1.8;

  friend bool operator==(const rectangle&, const rectangle&) = default;
};

/// Disc centred on the reference point (pedestrians; spec §2 default radius 0.35 m).
struct disc {
  double radius = 0.35;

  friend bool operator==(const disc&, const disc&) = default;
};

/// Convex polygon in the body frame (x forward, y left) [m], either orientation.
/// At least 3 and at most `max_polygon_vertices` vertices.
struct convex_polygon {
  std::vector<vec2> vertices;

  friend bool operator==(const convex_polygon&, const convex_polygon&) = default;
};

/// The shape a road user occupies, relative to its reference point and heading.
using footprint = std::variant<rectangle, disc, convex_polygon>;

inline constexpr std::size_t max_polygon_vertices = 16;

/// A footprint placed in the world: the Minkowski sum of a convex core (a single point when
/// `vertex_count == 1`, a segment when 2 — a drivable area's edge, `drivable_area.hpp` — else a
/// convex polygon) and a disc of `radius` [m].
/// Rectangles and polygons have radius 0; a disc is a point core with its radius.
struct placed_footprint {
  std::array<vec2, max_polygon_vertices> vertices{};
  std::size_t vertex_count = 0;
  double radius = 0.0;
  /// Set for rectangles, whose distances have closed forms: the centre, the unit heading, and the
  /// half length and half width [m].
  bool is_rectangle = false;
  vec2 centre;
  vec2 axis;
  double half_length = 0.0;
  double half_width = 0.0;
};

/// A rectangle placed in the world without its corner list: what the rectangle closed forms need.
/// The corners are computed as `place` computes them, so every distance below equals the one of
/// the corresponding `placed_footprint`s bit for bit.
struct placed_rectangle {
  vec2 centre;             ///< [m]
  vec2 axis;               ///< unit heading (cos θ, sin θ)
  double half_length = 0.0;  ///< [m]
  double half_width = 0.0;   ///< [m]
};

/// Largest separation of two rectangles along their four face normals [m]: a lower bound of their
/// signed distance, equal to it when they overlap (separating-axis theorem).
double face_separation(const placed_rectangle& a, const placed_rectangle& b);

/// `face_separation(a_i, b)` [m] of n rectangles a_i of half length `half.x` and half width `half.y`
/// [m], centred at (x[i], y[i]) with heading direction (c[i], s[i]), and `b`, into out[i]: two at a
/// time where the processor has SSE2, with the operations of `face_separation` in the same order,
/// so equal to it bit for bit (what `clearance_field` tests a block's samples with).
void face_separation_of_each(std::size_t n, const double* x, const double* y, const double* c, const double* s,
                             vec2 half, const placed_rectangle& b, double* out);

/// Distance of two rectangles that do not overlap [m]: the smallest distance from a corner of one
/// to the other (exact for convex shapes when they are apart). Two corners at a time where the
/// processor has SSE2: equal bit for bit to `corner_distance_reference`.
double corner_distance(const placed_rectangle& a, const placed_rectangle& b);

/// The reference for `corner_distance`: the eight corners one by one.
double corner_distance_reference(const placed_rectangle& a, const placed_rectangle& b);

/// Signed distance of two rectangles [m]: `face_separation` when ≤ 0, else `corner_distance`;
/// equal bit for bit to `signed_distance` of the placed footprints.
double signed_distance(const placed_rectangle& a, const placed_rectangle& b);

/// Signed distance [m] of a rectangle and a disc of `radius` [m] centred at `centre`: equal bit for
/// bit to `signed_distance` of the placed footprints.
double signed_distance(const placed_rectangle& r, vec2 centre, double radius);

/// `shape` placed at `where`.
placed_footprint place(const footprint& shape, const pose& where);

/// `shape` placed at `position` with heading direction (cos θ, sin θ) = `direction`; equal to
/// `place(shape, {position, θ})` bit for bit when `direction` is {cos θ, sin θ}.
placed_footprint place(const footprint& shape, vec2 position, vec2 direction);

/// Radius of the smallest disc about the reference point that contains the footprint [m].
double bounding_radius(const footprint& shape);

/// Smallest extent of the footprint [m]: rectangle width, disc diameter, polygon minimal width.
/// Bounds the collision time step so footprints cannot pass through each other (spec §5).
double smallest_dimension(const footprint& shape);

/// Why `shape` is not a valid footprint (sizes that are not positive and finite or exceed
/// `largest_footprint_size` of `input_bounds.hpp`, a polygon that is not convex or has fewer than 3 or more than
/// `max_polygon_vertices` vertices), or nothing.
std::optional<std::string> footprint_error(const footprint& shape);

/// True when the footprints overlap after inflating `b` by `margin` ≥ 0 [m] (spec §2): the
/// interiors intersect, or the gap between them is smaller than `margin`, i.e.
/// `signed_distance(a, b) < margin`. Touching is not overlap.
bool overlaps(const placed_footprint& a, const placed_footprint& b, double margin = 0.0);

/// Euclidean distance between the footprints [m]; 0 when they overlap.
double gap_distance(const placed_footprint& a, const placed_footprint& b);

/// Signed distance [m]: the gap when apart, minus the penetration depth (the shortest translation
/// that separates them) when they overlap. Continuous, and `overlaps(a, b, m)` ⇔ `signed_distance(a, b) < m`.
double signed_distance(const placed_footprint& a, const placed_footprint& b);

}  // namespace mm
