#include "mm/drivable_area.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "mm/number_text.hpp"

namespace mm {
namespace {

/// `signed_distance` of a rectangle and a segment, in the rectangle's frame: the segment's ends
/// there, the separating-axis test over the rectangle's two axes and the segment's normal, and when
/// apart the nearest of the ends to the box and of the box's corners to the segment.
///
/// First the case of a road's edge beside a car, in the segment's frame (unit direction e, normal
/// n): when the rectangle lies on one side of the segment's line, |n·(c − a)| ≥ h_n, and its
/// projection on the line within the segment, h_e ≤ e·(c − a) ≤ |b − a| − h_e, where
/// h_n = l|n·x| + w|n·y| and h_e = l|e·x| + w|e·y| are its half extents along n and e, its nearest
/// point to the line is nearest to the segment too: the distance is |n·(c − a)| − h_n.
double rectangle_signed_distance(const placed_footprint& f, const segment_line& line) {
  if (line.length > 0.0) {
    const vec2 e = line.direction;
    const double h_e = f.half_length * std::abs(dot(e, f.axis)) + f.half_width * std::abs(cross(e, f.axis));
    const double x = dot(e, f.centre - line.a);
    // |n·(c − a)| − h_n − radius, the radius 0 for a rectangle.
    const double gap = line_distance_bound(f, line);
    if (gap + f.radius >= 0.0 && x >= h_e && x <= line.length - h_e) return gap;
  }
  const auto local = [&](vec2 p) {
    const vec2 d = p - f.centre;
    return vec2{dot(d, f.axis), cross(f.axis, d)};
  };
  const vec2 p = local(line.a);
  const vec2 q = local(line.b);
  const double hl = f.half_length;
  const double hw = f.half_width;
  const vec2 along = q - p;
  const double length = norm(along);
  // The segment's extent against the box's along x, y and the segment's unit normal n.
  const double x_lo = std::min(p.x, q.x);
  const double x_hi = std::max(p.x, q.x);
  const double y_lo = std::min(p.y, q.y);
  const double y_hi = std::max(p.y, q.y);
  bool cuts = x_lo < hl && -hl < x_hi && y_lo < hw && -hw < y_hi;
  double n_depth = std::numeric_limits<double>::infinity();
  if (cuts && length > 0.0) {
    const vec2 n{-along.y / length, along.x / length};
    const double offset = dot(p, n);
    const double reach = hl * std::abs(n.x) + hw * std::abs(n.y);
    cuts = std::abs(offset) < reach;
    n_depth = reach - std::abs(offset);
  }
  if (cuts) {
    const double depth = std::min({hl - x_lo, x_hi + hl, hw - y_lo, y_hi + hw, n_depth});
    return -depth - f.radius;
  }
  const auto box_distance2 = [&](vec2 v) {
    const double dx = std::max(std::abs(v.x) - hl, 0.0);
    const double dy = std::max(std::abs(v.y) - hw, 0.0);
    return dx * dx + dy * dy;
  };
  // When the whole segment lies beyond a face's line (above the top face, say), a corner of the
  // opposite face is farther from every point of it than the corner across the rectangle from it on
  // that face, by a margin of the rectangle's size: it is not asked (a short edge beside the car
  // leaves two corners to ask, or one, or none).
  double best = std::min(box_distance2(p), box_distance2(q));
  const bool above = y_lo >= hw;
  const bool below = y_hi <= -hw;
  const bool ahead = x_lo >= hl;
  const bool behind = x_hi <= -hl;
  const bool in_slab_x = x_lo >= -hl && x_hi <= hl;
  const bool in_slab_y = y_lo >= -hw && y_hi <= hw;
  if ((in_slab_x && (above || below)) || (in_slab_y && (ahead || behind))) {
    // Within one face's slab: the nearest point of the segment to the face's line is an end.
    return std::sqrt(best) - f.radius;
  }
  for (const vec2 corner : {vec2{hl, hw}, vec2{-hl, hw}, vec2{-hl, -hw}, vec2{hl, -hw}}) {
    if ((above && corner.y < 0.0) || (below && corner.y > 0.0) || (ahead && corner.x < 0.0) ||
        (behind && corner.x > 0.0)) {
      continue;
    }
    best = std::min(best, squared_distance_to_segment(corner, p, q));
  }
  return std::sqrt(best) - f.radius;
}

/// Crossing-number test of `p` in a polygon (even-odd rule).
bool inside_polygon(const std::vector<vec2>& polygon, vec2 p) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const vec2 a = polygon[i];
    const vec2 b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

}  // namespace

std::optional<std::string> drivable_area_error(const std::vector<std::vector<vec2>>& polygons,
                                               const std::vector<polygon_edge>& open_edges) {
  if (polygons.empty()) return "no polygon; expected at least one polygon of at least 3 vertices";
  std::size_t vertices = 0;
  for (const std::vector<vec2>& p : polygons) vertices += p.size();
  if (vertices > largest_drivable_vertex_count) {
    return std::to_string(vertices) + " vertices in all; expected at most " +
           std::to_string(largest_drivable_vertex_count) + " (a road network of some hundred kilometres of lanes)";
  }
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const std::vector<vec2>& p = polygons[i];
    const std::string name = "polygons[" + std::to_string(i) + "]";
    if (p.size() < 3) {
      return name + " has " + std::to_string(p.size()) + " vertices; expected at least 3";
    }
    for (std::size_t j = 0; j < p.size(); ++j) {
      for (const double c : {p[j].x, p[j].y}) {
        if (!std::isfinite(c) || std::abs(c) > largest_drivable_coordinate) {
          return name + "[" + std::to_string(j) + "] = (" + number_text(p[j].x) + ", " + number_text(p[j].y) +
                 "); expected finite coordinates of at most 1e7 m in magnitude";
        }
      }
    }
    // The farthest vertex from the first, and the farthest from the line through both (twice the
    // largest triangle on that base), against the polygon's size: zero when every vertex lies on
    // one line.
    std::size_t far = 0;
    for (std::size_t j = 1; j < p.size(); ++j) {
      if (squared_norm(p[j] - p[0]) > squared_norm(p[far] - p[0])) far = j;
    }
    const double extent = norm(p[far] - p[0]);
    double largest = 0.0;
    for (std::size_t k = 1; k < p.size(); ++k) largest = std::max(largest, std::abs(cross(p[far] - p[0], p[k] - p[0])));
    if (!(largest > 1e-12 * extent * extent) || extent == 0.0) {
      return name + " has no area (its " + std::to_string(p.size()) +
             " vertices lie on one line); expected a polygon enclosing part of the road";
    }
  }
  for (std::size_t k = 0; k < open_edges.size(); ++k) {
    const polygon_edge& e = open_edges[k];
    if (e.polygon >= polygons.size() || e.edge >= polygons[e.polygon].size()) {
      return "open_edges[" + std::to_string(k) + "] = edge " + std::to_string(e.edge) + " of polygon " +
             std::to_string(e.polygon) + "; expected an edge of one of the " + std::to_string(polygons.size()) +
             " polygons (edge j from vertex j to the next)";
    }
  }
  return std::nullopt;
}

drivable_area::drivable_area(std::vector<std::vector<vec2>> polygons, const std::vector<polygon_edge>& open_edges)
    : polygons_(std::move(polygons)), open_edges_(open_edges) {
  if (auto error = drivable_area_error(polygons_, open_edges)) throw std::invalid_argument("drivable area: " + *error);
  boxes_.reserve(polygons_.size());
  for (const std::vector<vec2>& p : polygons_) {
    box b{p.front(), p.front()};
    for (const vec2 v : p) {
      b.lo = {std::min(b.lo.x, v.x), std::min(b.lo.y, v.y)};
      b.hi = {std::max(b.hi.x, v.x), std::max(b.hi.y, v.y)};
    }
    boxes_.push_back(b);
  }

  // Every edge, with its box widened by the closing distance.
  struct edge {
    segment s;
    box b;
    bool open;
    std::size_t polygon;
  };
  std::vector<edge> edges;
  for (std::size_t i = 0; i < polygons_.size(); ++i) {
    const std::vector<vec2>& p = polygons_[i];
    for (std::size_t j = 0; j < p.size(); ++j) {
      const segment s{p[j], p[(j + 1) % p.size()]};
      if (s.a == s.b) continue;
      const double w = drivable_area_closing;
      const bool open = std::find(open_edges.begin(), open_edges.end(), polygon_edge{i, j}) != open_edges.end();
      edges.push_back({s,
                       {{std::min(s.a.x, s.b.x) - w, std::min(s.a.y, s.b.y) - w},
                        {std::max(s.a.x, s.b.x) + w, std::max(s.a.y, s.b.y) + w}},
                       open,
                       i});
    }
  }
  // By the left end of their boxes, so that each edge meets only those that can reach it.
  std::vector<std::size_t> order(edges.size());
  for (std::size_t e = 0; e < order.size(); ++e) order[e] = e;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return edges[a].b.lo.x < edges[b].b.lo.x; });
  double widest = 0.0;
  for (const edge& e : edges) widest = std::max(widest, e.b.hi.x - e.b.lo.x);

  // A probe point next to an open edge counts as on the road: the road leads on there, and the
  // corners where open edges meet (lanelets ending side by side at the map's edge, their bounds a
  // few centimetres apart) leave no boundary.
  std::vector<segment> open_segments;
  for (const edge& e : edges) {
    if (e.open) open_segments.push_back(e.s);
  }
  const auto covered = [&](vec2 p) {
    if (contains(p)) return true;
    for (const segment& o : open_segments) {
      if (squared_distance_to_segment(p, o.a, o.b) <= 4.0 * drivable_area_closing * drivable_area_closing) return true;
    }
    return false;
  };
  // A point of an edge inside another polygon, farther than `interior_slack` from its edges, is not
  // on the union's boundary, whatever the probes say: where a lane meets another tangentially (a
  // roundabout's entry, a lanelet's fork), an edge runs on inside the other lane, closer to its edge
  // than the probes' reach, and is no edge of the road there.
  constexpr double interior_slack = 1e-6;
  const auto inside_another = [&](vec2 p, std::size_t own) {
    for (std::size_t i = 0; i < polygons_.size(); ++i) {
      const box& b = boxes_[i];
      if (i == own || p.x < b.lo.x || p.x > b.hi.x || p.y < b.lo.y || p.y > b.hi.y) continue;
      if (!inside_polygon(polygons_[i], p)) continue;
      const std::vector<vec2>& polygon = polygons_[i];
      bool clear = true;
      for (std::size_t j = 0; j < polygon.size() && clear; ++j) {
        clear = squared_distance_to_segment(p, polygon[j], polygon[(j + 1) % polygon.size()]) >
                interior_slack * interior_slack;
      }
      if (clear) return true;
    }
    return false;
  };
  std::vector<double> cuts;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (edges[e].open) continue;  // leads on beyond the map: never boundary
    const segment& s = edges[e].s;
    const vec2 along = s.b - s.a;
    const double length = norm(along);
    const vec2 unit = (1.0 / length) * along;
    const vec2 left{-unit.y, unit.x};
    // Where the edge may change between boundary and not: where another edge crosses it, and where
    // another edge's end comes within the closing distance of it.
    cuts.assign({0.0, 1.0});
    const auto cut_at = [&](double t) {
      if (t > 0.0 && t < 1.0) cuts.push_back(t);
    };
    const auto first = std::lower_bound(order.begin(), order.end(), edges[e].b.lo.x - widest,
                                        [&](std::size_t o, double x) { return edges[o].b.lo.x < x; });
    for (auto it = first; it != order.end() && edges[*it].b.lo.x <= edges[e].b.hi.x; ++it) {
      if (*it == e) continue;
      const edge& g = edges[*it];
      if (g.b.lo.y > edges[e].b.hi.y || g.b.hi.y < edges[e].b.lo.y || g.b.hi.x < edges[e].b.lo.x) continue;
      for (const vec2 end : {g.s.a, g.s.b}) {
        if (std::abs(dot(end - s.a, left)) <= drivable_area_closing) cut_at(dot(end - s.a, unit) / length);
      }
      const vec2 other = g.s.b - g.s.a;
      const double denominator = cross(along, other);
      if (denominator != 0.0) {
        const double t = cross(g.s.a - s.a, other) / denominator;
        const double u = cross(g.s.a - s.a, along) / denominator;
        if (u >= 0.0 && u <= 1.0) cut_at(t);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    // A piece is boundary when the union lies on one side of it and not on the other.
    std::size_t first_of_edge = boundary_.size();
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      if ((cuts[c + 1] - cuts[c]) * length <= 1e-9) continue;
      const vec2 middle = s.a + (0.5 * (cuts[c] + cuts[c + 1])) * along;
      const bool on_left = covered(middle + drivable_area_closing * left);
      const bool on_right = covered(middle - drivable_area_closing * left);
      if (on_left == on_right || inside_another(middle, edges[e].polygon)) continue;
      const vec2 from = s.a + cuts[c] * along;
      const vec2 to = s.a + cuts[c + 1] * along;
      // Consecutive boundary pieces of one edge are one segment.
      if (boundary_.size() > first_of_edge && boundary_.back().b == from) {
        boundary_.back().b = to;
      } else {
        boundary_.push_back({from, to});
      }
      first_of_edge = boundary_.size() - 1;
    }
  }
  boundary_lines_.reserve(boundary_.size());
  for (const segment& s : boundary_) boundary_lines_.emplace_back(s);
}

bool drivable_area::contains(vec2 p) const {
  for (std::size_t i = 0; i < polygons_.size(); ++i) {
    const box& b = boxes_[i];
    if (p.x < b.lo.x || p.x > b.hi.x || p.y < b.lo.y || p.y > b.hi.y) continue;
    if (inside_polygon(polygons_[i], p)) return true;
  }
  return false;
}

double signed_distance(const placed_footprint& f, const segment& s) {
  if (f.is_rectangle) return rectangle_signed_distance(f, segment_line(s));
  return signed_distance_reference(f, s);
}

double signed_distance(const placed_footprint& f, const segment_line& line) {
  if (f.is_rectangle) return rectangle_signed_distance(f, line);
  return signed_distance_reference(f, line.segment_of());
}

double signed_distance_reference(const placed_footprint& f, const segment& s) {
  // The segment as a core of two vertices (one when it is a point), for the general form.
  placed_footprint edge;
  edge.vertices[0] = s.a;
  edge.vertices[1] = s.b;
  edge.vertex_count = s.a == s.b ? 1 : 2;
  return signed_distance(f, edge);
}

segment_line::segment_line(const segment& s) : a(s.a), b(s.b), length(norm(s.b - s.a)) {
  if (length > 0.0) direction = (1.0 / length) * (s.b - s.a);
}

double line_distance_bound(const placed_footprint& f, const segment_line& line) {
  if (!f.is_rectangle || line.direction == vec2{}) return -std::numeric_limits<double>::infinity();
  const vec2 e = line.direction;
  const double h_n = f.half_length * std::abs(cross(e, f.axis)) + f.half_width * std::abs(dot(e, f.axis));
  return std::abs(cross(e, f.centre - line.a)) - h_n - f.radius;
}

namespace {

/// A disc that holds a footprint: about a rectangle's centre, or a polygon's vertex mean [m].
struct bounding_disc {
  vec2 centre;
  double radius = 0.0;
};

bounding_disc disc_around(const placed_footprint& f) {
  if (f.is_rectangle) {
    return {f.centre, std::sqrt(f.half_length * f.half_length + f.half_width * f.half_width) * (1.0 + 1e-12) + f.radius};
  }
  vec2 centre;
  for (std::size_t i = 0; i < f.vertex_count; ++i) centre = centre + f.vertices[i];
  centre = (1.0 / static_cast<double>(f.vertex_count)) * centre;
  double radius = 0.0;
  for (std::size_t i = 0; i < f.vertex_count; ++i) radius = std::max(radius, norm(f.vertices[i] - centre));
  return {centre, radius + f.radius};
}

/// min(best, the signed distance of `f` to `line`): a segment farther than the best so far from the
/// line's bound or the disc cannot lower the minimum, and is not asked.
double lowered(const placed_footprint& f, const bounding_disc& disc, const segment_line& line, double best) {
  const double slack = 1e-9 * (1.0 + std::abs(best));
  if (line_distance_bound(f, line) > best + slack) return best;
  const double far = std::sqrt(squared_distance_to_segment(disc.centre, line.a, line.b)) - disc.radius;
  if (far > best + slack) return best;
  return std::min(best, signed_distance(f, line));
}

}  // namespace

double boundary_clearance(std::span<const segment> boundary, const placed_footprint& f, double cap) {
  const bounding_disc disc = disc_around(f);
  double best = cap;
  for (const segment& s : boundary) best = lowered(f, disc, segment_line(s), best);
  return best;
}

double boundary_clearance(std::span<const segment_line> boundary, const placed_footprint& f, double cap) {
  const bounding_disc disc = disc_around(f);
  double best = cap;
  for (const segment_line& line : boundary) best = lowered(f, disc, line, best);
  return best;
}

}  // namespace mm
