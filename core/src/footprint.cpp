#include "mm/footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "mm/number_text.hpp"

namespace mm {
namespace {

struct interval {
  double lo;
  double hi;
};

interval project(const placed_footprint& f, vec2 axis) {
  interval result{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < f.vertex_count; ++i) {
    const double p = dot(f.vertices[i], axis);
    result.lo = std::min(result.lo, p);
    result.hi = std::max(result.hi, p);
  }
  return result;
}

/// True when some edge normal of `f` separates the cores of `f` and `g` (touching counts as separated);
/// a segment's two edges give its normal.
bool has_separating_edge(const placed_footprint& f, const placed_footprint& g) {
  if (f.vertex_count < 2) return false;
  for (std::size_t i = 0; i < f.vertex_count; ++i) {
    const vec2 edge = f.vertices[(i + 1) % f.vertex_count] - f.vertices[i];
    const vec2 axis{-edge.y, edge.x};
    const interval pf = project(f, axis);
    const interval pg = project(g, axis);
    if (pf.hi <= pg.lo || pg.hi <= pf.lo) return true;
  }
  return false;
}

/// True when the point `p` lies strictly inside the convex polygon core of `f`.
bool strictly_inside(const placed_footprint& f, vec2 p) {
  if (f.vertex_count < 3) return false;
  int sign = 0;
  for (std::size_t i = 0; i < f.vertex_count; ++i) {
    const vec2 a = f.vertices[i];
    const vec2 b = f.vertices[(i + 1) % f.vertex_count];
    const double c = cross(b - a, p - a);
    if (c == 0.0) return false;
    const int s = c > 0.0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign) return false;
  }
  return true;
}

/// True when the interiors of the two cores intersect.
bool cores_intersect(const placed_footprint& a, const placed_footprint& b) {
  if (a.vertex_count == 1 && b.vertex_count == 1) return false;
  if (a.vertex_count == 1) return strictly_inside(b, a.vertices[0]);
  if (b.vertex_count == 1) return strictly_inside(a, b.vertices[0]);
  return !has_separating_edge(a, b) && !has_separating_edge(b, a);
}

/// Smallest squared distance from the vertices of `f` to the boundary of the core of `g`.
double squared_vertex_to_boundary(const placed_footprint& f, const placed_footprint& g) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < f.vertex_count; ++i) {
    if (g.vertex_count == 1) {
      best = std::min(best, squared_norm(f.vertices[i] - g.vertices[0]));
      continue;
    }
    for (std::size_t j = 0; j < g.vertex_count; ++j) {
      best = std::min(best, squared_distance_to_segment(f.vertices[i], g.vertices[j],
                                                        g.vertices[(j + 1) % g.vertex_count]));
    }
  }
  return best;
}

/// Distance between two cores whose interiors do not intersect.
double separated_core_distance(const placed_footprint& a, const placed_footprint& b) {
  return std::sqrt(std::min(squared_vertex_to_boundary(a, b), squared_vertex_to_boundary(b, a)));
}

/// Penetration depth of two cores whose interiors intersect: the smallest overlap of their
/// projections over the edge normals (exact for convex polygons), or the depth of a point core.
double core_penetration(const placed_footprint& a, const placed_footprint& b) {
  if (a.vertex_count == 1) return std::sqrt(squared_vertex_to_boundary(a, b));
  if (b.vertex_count == 1) return std::sqrt(squared_vertex_to_boundary(b, a));
  double depth = std::numeric_limits<double>::infinity();
  for (const placed_footprint* f : {&a, &b}) {
    for (std::size_t i = 0; i < f->vertex_count; ++i) {
      const vec2 edge = f->vertices[(i + 1) % f->vertex_count] - f->vertices[i];
      const double length = norm(edge);
      if (length == 0.0) continue;
      const vec2 axis{-edge.y / length, edge.x / length};
      const interval pa = project(a, axis);
      const interval pb = project(b, axis);
      depth = std::min(depth, std::min(pa.hi - pb.lo, pb.hi - pa.lo));
    }
  }
  return depth;
}

/// `p` in the frame of rectangle `r` (x along its heading).
vec2 in_frame(const placed_rectangle& r, vec2 p) {
  const vec2 d = p - r.centre;
  return {dot(d, r.axis), cross(r.axis, d)};
}

/// Squared distance from a point given in a rectangle's frame to the rectangle (0 inside).
double squared_distance_to_box(vec2 local, const placed_rectangle& r) {
  const double dx = std::max(std::abs(local.x) - r.half_length, 0.0);
  const double dy = std::max(std::abs(local.y) - r.half_width, 0.0);
  return dx * dx + dy * dy;
}

placed_rectangle as_rectangle(const placed_footprint& f) {
  return {f.centre, f.axis, f.half_length, f.half_width};
}

/// Signed distance of a point (the core of a disc) to a rectangle, before subtracting radii.
double point_rectangle_signed_distance(vec2 p, const placed_rectangle& r) {
  const vec2 local = in_frame(r, p);
  const double inside_x = r.half_length - std::abs(local.x);
  const double inside_y = r.half_width - std::abs(local.y);
  if (inside_x > 0.0 && inside_y > 0.0) return -std::min(inside_x, inside_y);
  return std::sqrt(squared_distance_to_box(local, r));
}

double polygon_width(const std::vector<vec2>& v) {
  double width = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const vec2 edge = v[(i + 1) % v.size()] - v[i];
    const double len = norm(edge);
    if (len == 0.0) continue;
    double extent = 0.0;
    for (const vec2& p : v) extent = std::max(extent, std::abs(cross(edge, p - v[i])) / len);
    width = std::min(width, extent);
  }
  return width;
}

}  // namespace

placed_footprint place(const footprint& shape, const pose& where) {
  return place(shape, where.position, {std::cos(where.heading), std::sin(where.heading)});
}

placed_footprint place(const footprint& shape, vec2 position, vec2 direction) {
  placed_footprint placed;
  const double c = direction.x;
  const double s = direction.y;
  const auto put = [&](const std::vector<vec2>& body) {
    placed.vertex_count = std::min(body.size(), max_polygon_vertices);
    for (std::size_t i = 0; i < placed.vertex_count; ++i) {
      placed.vertices[i] = position + rotated(body[i], c, s);
    }
  };
  if (const auto* r = std::get_if<rectangle>(&shape)) {
    const double hl = r->length / 2.0;
    const double hw = r->width / 2.0;
    const vec2 along{c * hl, s * hl};
    const vec2 across{-s * hw, c * hw};
    placed.vertex_count = 4;
    placed.is_rectangle = true;
    placed.centre = position;
    placed.axis = direction;
    placed.half_length = hl;
    placed.half_width = hw;
    placed.vertices[0] = position + along + across;
    placed.vertices[1] = position - along + across;
    placed.vertices[2] = position - along - across;
    placed.vertices[3] = position + along - across;
  } else if (const auto* d = std::get_if<disc>(&shape)) {
    placed.vertex_count = 1;
    placed.vertices[0] = position;
    placed.radius = d->radius;
  } else {
    put(std::get<convex_polygon>(shape).vertices);
  }
  return placed;
}

double bounding_radius(const footprint& shape) {
  if (const auto* r = std::get_if<rectangle>(&shape)) return std::hypot(r->length, r->width) / 2.0;
  if (const auto* d = std::get_if<disc>(&shape)) return d->radius;
  double radius = 0.0;
  for (const vec2& v : std::get<convex_polygon>(shape).vertices) radius = std::max(radius, norm(v));
  return radius;
}

double smallest_dimension(const footprint& shape) {
  if (const auto* r = std::get_if<rectangle>(&shape)) return std::min(r->length, r->width);
  if (const auto* d = std::get_if<disc>(&shape)) return 2.0 * d->radius;
  return polygon_width(std::get<convex_polygon>(shape).vertices);
}

std::optional<std::string> footprint_error(const footprint& shape) {
  const auto size_error = [](const char* what, double v) -> std::optional<std::string> {
    if (std::isfinite(v) && v > 0.0 && v <= largest_footprint_size) return std::nullopt;
    return std::string(what) + " must be a positive number of metres up to " + number_text(largest_footprint_size) +
           ", got " + number_text(v);
  };
  if (const auto* r = std::get_if<rectangle>(&shape)) {
    if (auto e = size_error("rectangle length", r->length)) return e;
    return size_error("rectangle width", r->width);
  }
  if (const auto* d = std::get_if<disc>(&shape)) return size_error("disc radius", d->radius);
  const auto& v = std::get<convex_polygon>(shape).vertices;
  if (v.size() < 3 || v.size() > max_polygon_vertices) {
    return "polygon must have 3 to " + std::to_string(max_polygon_vertices) + " vertices, got " +
           std::to_string(v.size());
  }
  for (const vec2& p : v) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::string("polygon vertex is not finite");
    if (std::abs(p.x) > largest_footprint_size || std::abs(p.y) > largest_footprint_size) {
      return "polygon vertex (" + number_text(p.x) + ", " + number_text(p.y) + ") lies more than " +
             number_text(largest_footprint_size) + " m from the reference point";
    }
  }
  int sign = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const vec2 a = v[i];
    const vec2 b = v[(i + 1) % v.size()];
    const vec2 c = v[(i + 2) % v.size()];
    const double turn = cross(b - a, c - b);
    if (turn == 0.0) continue;
    const int s = turn > 0.0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign) return "polygon is not convex (turn direction changes at vertex " + std::to_string((i + 1) % v.size()) + ")";
  }
  if (sign == 0) return std::string("polygon has zero area (all vertices on one line)");
  double turning = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const vec2 e0 = v[(i + 1) % v.size()] - v[i];
    const vec2 e1 = v[(i + 2) % v.size()] - v[(i + 1) % v.size()];
    turning += std::atan2(cross(e0, e1), dot(e0, e1));
  }
  if (std::abs(std::abs(turning) - 2.0 * std::numbers::pi) > 1e-6) {
    return std::string("polygon is self-intersecting (its edges turn more than once around)");
  }
  return std::nullopt;
}

double face_separation(const placed_rectangle& a, const placed_rectangle& b) {
  const vec2 d = b.centre - a.centre;
  const vec2 a_side{-a.axis.y, a.axis.x};
  const vec2 b_side{-b.axis.y, b.axis.x};
  const double c = std::abs(dot(a.axis, b.axis));   // |cos| of the angle between them
  const double s = std::abs(cross(a.axis, b.axis)); // |sin|
  const double along_a = std::abs(dot(d, a.axis)) - a.half_length - (b.half_length * c + b.half_width * s);
  const double side_a = std::abs(dot(d, a_side)) - a.half_width - (b.half_length * s + b.half_width * c);
  const double along_b = std::abs(dot(d, b.axis)) - b.half_length - (a.half_length * c + a.half_width * s);
  const double side_b = std::abs(dot(d, b_side)) - b.half_width - (a.half_length * s + a.half_width * c);
  return std::max(std::max(along_a, side_a), std::max(along_b, side_b));
}

void face_separation_of_each(std::size_t n, const double* x, const double* y, const double* c, const double* s,
                             vec2 half, const placed_rectangle& b, double* out) {
  std::size_t i = 0;
#if defined(__SSE2__)
  // Lane by lane `face_separation(a_i, b)`: std::abs is the cleared sign bit, std::max(u, v) is
  // maxpd(v, u) (the same operand on ties, signed zeros included).
  const __m128d sign = _mm_set1_pd(-0.0);
  const __m128d bx = _mm_set1_pd(b.axis.x);
  const __m128d by = _mm_set1_pd(b.axis.y);
  const __m128d neg_by = _mm_set1_pd(-b.axis.y);
  const __m128d centre_x = _mm_set1_pd(b.centre.x);
  const __m128d centre_y = _mm_set1_pd(b.centre.y);
  const __m128d a_length = _mm_set1_pd(half.x);
  const __m128d a_width = _mm_set1_pd(half.y);
  const __m128d b_length = _mm_set1_pd(b.half_length);
  const __m128d b_width = _mm_set1_pd(b.half_width);
  const auto max = [](__m128d u, __m128d v) { return _mm_max_pd(v, u); };
  const auto abs = [&](__m128d v) { return _mm_andnot_pd(sign, v); };
  for (; i + 2 <= n; i += 2) {
    const __m128d ax = _mm_loadu_pd(c + i);
    const __m128d ay = _mm_loadu_pd(s + i);
    const __m128d dx = _mm_sub_pd(centre_x, _mm_loadu_pd(x + i));
    const __m128d dy = _mm_sub_pd(centre_y, _mm_loadu_pd(y + i));
    const __m128d cosine = abs(_mm_add_pd(_mm_mul_pd(ax, bx), _mm_mul_pd(ay, by)));
    const __m128d sine = abs(_mm_sub_pd(_mm_mul_pd(ax, by), _mm_mul_pd(ay, bx)));
    const __m128d along_a = _mm_sub_pd(_mm_sub_pd(abs(_mm_add_pd(_mm_mul_pd(dx, ax), _mm_mul_pd(dy, ay))), a_length),
                                       _mm_add_pd(_mm_mul_pd(b_length, cosine), _mm_mul_pd(b_width, sine)));
    const __m128d side_a =
        _mm_sub_pd(_mm_sub_pd(abs(_mm_add_pd(_mm_mul_pd(dx, _mm_xor_pd(ay, sign)), _mm_mul_pd(dy, ax))), a_width),
                   _mm_add_pd(_mm_mul_pd(b_length, sine), _mm_mul_pd(b_width, cosine)));
    const __m128d along_b = _mm_sub_pd(_mm_sub_pd(abs(_mm_add_pd(_mm_mul_pd(dx, bx), _mm_mul_pd(dy, by))), b_length),
                                       _mm_add_pd(_mm_mul_pd(a_length, cosine), _mm_mul_pd(a_width, sine)));
    const __m128d side_b = _mm_sub_pd(_mm_sub_pd(abs(_mm_add_pd(_mm_mul_pd(dx, neg_by), _mm_mul_pd(dy, bx))), b_width),
                                      _mm_add_pd(_mm_mul_pd(a_length, sine), _mm_mul_pd(a_width, cosine)));
    _mm_storeu_pd(out + i, max(max(along_a, side_a), max(along_b, side_b)));
  }
#endif
  for (; i < n; ++i) out[i] = face_separation(placed_rectangle{{x[i], y[i]}, {c[i], s[i]}, half.x, half.y}, b);
}

namespace {

/// The offset, half-length and half-width vectors of each rectangle in the other's frame, from the
/// centres' offset and the relative heading (cos c, sin s): a corner is centre ± along ± across.
struct corner_frames {
  vec2 b_centre, b_along, b_across;  ///< b in a's frame
  vec2 a_centre, a_along, a_across;  ///< a in b's frame
};

corner_frames frames_of(const placed_rectangle& a, const placed_rectangle& b) {
  const vec2 d = b.centre - a.centre;
  const double c = dot(a.axis, b.axis);
  const double s = cross(a.axis, b.axis);
  return {{dot(d, a.axis), cross(a.axis, d)},
          {b.half_length * c, b.half_length * s},
          {-b.half_width * s, b.half_width * c},
          {-dot(d, b.axis), -cross(b.axis, d)},
          {a.half_length * c, -a.half_length * s},
          {a.half_width * s, a.half_width * c}};
}

#if defined(__SSE2__)
/// The smaller squared distances to the box of half sides (`length`, `width`) of the corners
/// centre ± along + across (lane 0) and centre ± along − across (lane 1): `squared_distance_to_box`
/// lane by lane, with the same operations in the same order (std::max(v, 0) is maxpd(0, v) and
/// std::min(u, v) is minpd(v, u), signed zeros included), so bit for bit the scalar values.
__m128d corner_squares(vec2 centre, vec2 along, vec2 across, double length, double width) {
  const __m128d sign = _mm_set1_pd(-0.0);
  const __m128d zero = _mm_setzero_pd();
  const __m128d across_x = _mm_set_pd(-across.x, across.x);
  const __m128d across_y = _mm_set_pd(-across.y, across.y);
  const __m128d plus_x = _mm_add_pd(_mm_set1_pd(centre.x + along.x), across_x);
  const __m128d plus_y = _mm_add_pd(_mm_set1_pd(centre.y + along.y), across_y);
  const __m128d minus_x = _mm_add_pd(_mm_set1_pd(centre.x + -along.x), across_x);
  const __m128d minus_y = _mm_add_pd(_mm_set1_pd(centre.y + -along.y), across_y);
  const __m128d half_length = _mm_set1_pd(length);
  const __m128d half_width = _mm_set1_pd(width);
  const auto squared = [&](__m128d x, __m128d y) {
    const __m128d dx = _mm_max_pd(zero, _mm_sub_pd(_mm_andnot_pd(sign, x), half_length));
    const __m128d dy = _mm_max_pd(zero, _mm_sub_pd(_mm_andnot_pd(sign, y), half_width));
    return _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
  };
  return _mm_min_pd(squared(minus_x, minus_y), squared(plus_x, plus_y));
}
#endif

}  // namespace

double corner_distance(const placed_rectangle& a, const placed_rectangle& b) {
#if defined(__SSE2__)
  // The eight corners two at a time: 15 instead of 25 ns a call on this project's benchmark
  // machine (docs/performance.md), equal bit for bit to `corner_distance_reference`.
  const corner_frames f = frames_of(a, b);
  const __m128d m = _mm_min_pd(corner_squares(f.a_centre, f.a_along, f.a_across, b.half_length, b.half_width),
                               corner_squares(f.b_centre, f.b_along, f.b_across, a.half_length, a.half_width));
  return std::sqrt(_mm_cvtsd_f64(_mm_min_sd(_mm_unpackhi_pd(m, m), m)));
#else
  return corner_distance_reference(a, b);
#endif
}

double corner_distance_reference(const placed_rectangle& a, const placed_rectangle& b) {
  const corner_frames f = frames_of(a, b);
  double best = std::numeric_limits<double>::infinity();
  for (const double along : {1.0, -1.0}) {
    for (const double across : {1.0, -1.0}) {
      best = std::min(best, squared_distance_to_box(f.b_centre + along * f.b_along + across * f.b_across, a));
      best = std::min(best, squared_distance_to_box(f.a_centre + along * f.a_along + across * f.a_across, b));
    }
  }
  return std::sqrt(best);
}

double signed_distance(const placed_rectangle& a, const placed_rectangle& b) {
  const double separation = face_separation(a, b);
  if (separation <= 0.0) return separation;
  return corner_distance(a, b);
}

double signed_distance(const placed_rectangle& r, vec2 centre, double radius) {
  return point_rectangle_signed_distance(centre, r) - radius;
}

bool overlaps(const placed_footprint& a, const placed_footprint& b, double margin) {
  return signed_distance(a, b) < margin;
}

double signed_distance(const placed_footprint& a, const placed_footprint& b) {
  if (a.is_rectangle && b.is_rectangle) return signed_distance(as_rectangle(a), as_rectangle(b));
  if (a.is_rectangle && b.vertex_count == 1) return signed_distance(as_rectangle(a), b.vertices[0], b.radius);
  if (b.is_rectangle && a.vertex_count == 1) return signed_distance(as_rectangle(b), a.vertices[0], a.radius);
  if (cores_intersect(a, b)) return -core_penetration(a, b) - a.radius - b.radius;
  return separated_core_distance(a, b) - a.radius - b.radius;
}

double gap_distance(const placed_footprint& a, const placed_footprint& b) {
  return std::max(0.0, signed_distance(a, b));
}

}  // namespace mm
