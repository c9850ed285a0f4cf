#include "mm/translation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace mm {
namespace {

/// The line c + b·s.
struct line {
  double c;
  double b;
};

/// Lowest point on [0, duration] of the upper envelope max_j (c_j + b_j s) of `lines`: convex and
/// piecewise linear, so from s = 0 the walk follows the line that rises slowest among those on top
/// (its right derivative) until a steeper one overtakes it, and stops where the envelope stops
/// falling. Each step moves to a strictly steeper line: at most `count` steps.
template <std::size_t count_limit = 0>
translation_minimum lowest_on_envelope(const line* lines, std::size_t runtime_count, double duration) {
  // A fixed count (the rectangle forms' eight or four lines) lets the loops unroll.
  const std::size_t count = count_limit > 0 ? count_limit : runtime_count;
  std::size_t active = 0;
  for (std::size_t j = 1; j < count; ++j) {
    if (lines[j].c > lines[active].c || (lines[j].c == lines[active].c && lines[j].b > lines[active].b)) active = j;
  }
  double s = 0.0;
  for (std::size_t step = 0; step < count && lines[active].b < 0.0; ++step) {
    // The first crossing x = (c_a − c_j)/(b_j − b_a) of a steeper line, compared by cross-multiplying
    // (the denominators are positive): one division per step.
    const double ca = lines[active].c;
    const double ba = lines[active].b;
    double num = 0.0;
    double den = 0.0;
    std::size_t steeper = count;
    for (std::size_t j = 0; j < count; ++j) {
      const double rise = lines[j].b - ba;
      if (!(rise > 0.0)) continue;
      const double n = ca - lines[j].c;
      if (steeper == count || n * den < num * rise || (n * den == num * rise && lines[j].b > lines[steeper].b)) {
        num = n;
        den = rise;
        steeper = j;
      }
    }
    if (steeper == count) {
      s = duration;
      break;
    }
    const double next = num / den;
    if (!(next < duration)) {
      s = duration;
      break;
    }
    s = std::max(s, next);
    active = steeper;
  }
  double value = lines[0].c + lines[0].b * s;
  for (std::size_t j = 1; j < count; ++j) value = std::max(value, lines[j].c + lines[j].b * s);
  return {value, s};
}

/// Smallest squared distance [m²] over s ∈ [0, duration] of the point `offset` + `velocity`·s from
/// the origin, and its s.
translation_minimum closest_approach_squared(vec2 offset, vec2 velocity, double duration) {
  const double speed_squared = squared_norm(velocity);
  const double s = speed_squared > 0.0 ? std::clamp(-dot(offset, velocity) / speed_squared, 0.0, duration) : 0.0;
  return {squared_norm(offset + s * velocity), s};
}

/// The corners of a placed rectangle, as `place` computes them.
std::array<vec2, 4> corners(const placed_rectangle& r) {
  const vec2 along{r.axis.x * r.half_length, r.axis.y * r.half_length};
  const vec2 across{-r.axis.y * r.half_width, r.axis.x * r.half_width};
  return {r.centre + along + across, r.centre - along + across, r.centre - along - across, r.centre + along - across};
}

/// The lower of two minima (the earlier on a tie).
translation_minimum lower(translation_minimum x, translation_minimum y) { return y.distance < x.distance ? y : x; }

/// Bisection for the earliest s with `distance_at(s)` ≤ level, given the minimum of the convex
/// `distance_at` on [0, duration].
template <class DistanceAt>
double earliest_at_or_below(DistanceAt&& distance_at, const translation_minimum& minimum, double level) {
  if (distance_at(0.0) <= level) return 0.0;
  if (minimum.distance > level) return std::numeric_limits<double>::infinity();
  double lo = 0.0;
  double hi = minimum.time;
  while (hi - lo > 1e-9) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (distance_at(mid) <= level ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

double closest_approach_to_growing_disc(vec2 offset, vec2 velocity, double growth, double duration) {
  const double a = squared_norm(velocity);
  const double b = dot(offset, velocity);
  const auto at = [&](double s) { return norm(offset + s * velocity) - growth * s; };
  // The distance changes at most at |velocity|: no faster than the disc grows, it only falls.
  if (a <= growth * growth) return at(duration);
  // (b + a s)² = growth² |offset + velocity s|² = growth² ((b + a s)² + |offset × velocity|²) / a.
  const double across = cross(offset, velocity);
  const double u = growth * std::sqrt(across * across / (a - growth * growth));
  return at(std::clamp((u - b) / a, 0.0, duration));
}

placed_rectangle moved(const placed_rectangle& a, vec2 displacement) {
  return {a.centre + displacement, a.axis, a.half_length, a.half_width};
}

placed_footprint moved(const placed_footprint& a, vec2 displacement) {
  placed_footprint m = a;
  for (std::size_t i = 0; i < m.vertex_count; ++i) m.vertices[i] = m.vertices[i] + displacement;
  m.centre = m.centre + displacement;
  return m;
}

namespace {

translation_minimum apart_minimum(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                                  const face_separations& separations);
translation_minimum apart_minimum(const placed_rectangle& a, vec2 centre, double radius, const translation& motion);

}  // namespace

face_separations::face_separations(const placed_rectangle& a, const placed_rectangle& b, const translation& motion)
    : count_(4), duration_(motion.duration) {
  const vec2 offset = a.centre - b.centre;
  const vec2 a_side{-a.axis.y, a.axis.x};
  const vec2 b_side{-b.axis.y, b.axis.x};
  const double c = std::abs(dot(a.axis, b.axis));
  const double s = std::abs(cross(a.axis, b.axis));
  const std::array<vec2, 4> normals{a.axis, a_side, b.axis, b_side};
  const std::array<double, 4> half_extents{a.half_length + (b.half_length * c + b.half_width * s),
                                           a.half_width + (b.half_length * s + b.half_width * c),
                                           b.half_length + (a.half_length * c + a.half_width * s),
                                           b.half_width + (a.half_length * s + a.half_width * c)};
  for (std::size_t n = 0; n < 4; ++n) {
    slabs_[n] = {dot(offset, normals[n]), dot(motion.velocity, normals[n]), half_extents[n]};
  }
}

face_separations::face_separations(const placed_rectangle& a, vec2 centre, double radius, const translation& motion)
    : count_(2), duration_(motion.duration) {
  // The disc's centre in a's frame, as a point: its offset along a's two axes, each widened by the radius.
  const vec2 offset = a.centre - centre;
  const vec2 side{-a.axis.y, a.axis.x};
  slabs_[0] = {dot(offset, a.axis), dot(motion.velocity, a.axis), a.half_length + radius};
  slabs_[1] = {dot(offset, side), dot(motion.velocity, side), a.half_width + radius};
}

bool face_separations::reach(const widening& level) const {
  // |p + q s| − h ≤ L₀ + L₁ s on both sides: (q − L₁) s ≤ h + L₀ − p and (−q − L₁) s ≤ h + L₀ + p,
  // each a half-line of times; they meet within [0, duration] or not.
  double lo = 0.0;
  double hi = duration_;
  bool empty = false;
  const auto bound = [&](double alpha, double beta) {  // α s ≤ β
    if (alpha > 0.0) {
      hi = std::min(hi, beta / alpha);
    } else if (alpha < 0.0) {
      lo = std::max(lo, beta / alpha);
    } else if (beta < 0.0) {
      empty = true;
    }
  };
  for (std::size_t n = 0; n < count_; ++n) {
    const slab& f = slabs_[n];
    const double room = f.half_extent + level.base;
    bound(f.rate - level.rate, room - f.offset);
    bound(-f.rate - level.rate, room + f.offset);
  }
  return !empty && lo <= hi;
}

double face_separations::at(double s) const {
  double separation = -std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < count_; ++n) {
    const slab& f = slabs_[n];
    separation = std::max(separation, std::abs(f.offset + f.rate * s) - f.half_extent);
  }
  return separation;
}

bool face_separations::reach(double level) const {
  if (!inverted_) {
    for (std::size_t n = 0; n < count_; ++n) inverse_rates_[n] = slabs_[n].rate != 0.0 ? 1.0 / slabs_[n].rate : 0.0;
    inverted_ = true;
  }
  // |p + q s| ≤ h + level between the times (±(h + level) − p)/q.
  double lo = 0.0;
  double hi = duration_;
  for (std::size_t n = 0; n < count_; ++n) {
    const slab& f = slabs_[n];
    const double room = f.half_extent + level;
    if (!(room >= 0.0)) return false;
    if (f.rate == 0.0) {
      if (!(std::abs(f.offset) <= room)) return false;
      continue;
    }
    const double first = (-room - f.offset) * inverse_rates_[n];
    const double second = (room - f.offset) * inverse_rates_[n];
    lo = std::max(lo, std::min(first, second));
    hi = std::min(hi, std::max(first, second));
  }
  return lo <= hi;
}

translation_minimum face_separations::lowest(const widening& less) const {
  std::array<line, 8> lines{};
  for (std::size_t n = 0; n < count_; ++n) {
    const slab& f = slabs_[n];
    lines[2 * n] = {f.offset - f.half_extent - less.base, f.rate - less.rate};
    lines[2 * n + 1] = {-f.offset - f.half_extent - less.base, -f.rate - less.rate};
  }
  return count_ == 4 ? lowest_on_envelope<8>(lines.data(), 8, duration_) : lowest_on_envelope<4>(lines.data(), 4, duration_);
}

translation_minimum smallest_face_separation(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const widening& less) {
  return face_separations(a, b, motion).lowest(less);
}

translation_minimum smallest_face_separation(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion, const widening& less) {
  return face_separations(a, centre, radius, motion).lowest(less);
}

bool face_separation_reaches(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                             const widening& level) {
  return face_separations(a, b, motion).reach(level);
}

bool face_separation_reaches(const placed_rectangle& a, vec2 centre, double radius, const translation& motion,
                             const widening& level) {
  return face_separations(a, centre, radius, motion).reach(level);
}

translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion) {
  return smallest_signed_distance(a, b, motion, smallest_face_separation(a, b, motion));
}

translation_minimum smallest_signed_distance(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion) {
  return smallest_signed_distance(a, centre, radius, motion, smallest_face_separation(a, centre, radius, motion));
}

bool signed_distance_reaches(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                             double level) {
  const face_separations separations(a, b, motion);
  if (!separations.reach(level)) return false;
  if (level <= 0.0 || separations.reach(0.0)) return true;  // overlapping: it is the distance
  return apart_minimum(a, b, motion, separations).distance <= level;
}

bool signed_distance_reaches(const placed_rectangle& a, vec2 centre, double radius, const translation& motion,
                             double level) {
  // The disc's centre inside the rectangle where its separation is ≤ −radius.
  const face_separations separations(a, centre, radius, motion);
  if (!separations.reach(level)) return false;
  if (level + radius <= 0.0 || separations.reach(-radius)) return true;
  return apart_minimum(a, centre, radius, motion).distance <= level;
}

translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const translation_minimum& separation) {
  if (separation.distance <= 0.0) return separation;
  return apart_minimum(a, b, motion, face_separations(a, b, motion));
}

translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const face_separations& separations) {
  const translation_minimum separation = separations.lowest();
  if (separation.distance <= 0.0) return separation;
  return apart_minimum(a, b, motion, separations);
}

namespace {

translation_minimum apart_minimum(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                                  const face_separations& separations) {
  // Apart all along: every pair of corners along the motion, then the ends where their face
  // separation (a lower bound of their distance) is below the closest pair.
  // In the frame of the motion (x along it), a pair's offset (x, y) moves to (x + v s, y).
  const vec2 w = motion.velocity;
  const double duration = motion.duration;
  const double speed = norm(w);
  const vec2 along = speed > 0.0 ? (1.0 / speed) * w : vec2{1.0, 0.0};
  const std::array<vec2, 4> mine = corners(a);
  const std::array<vec2, 4> theirs = corners(b);
  std::array<vec2, 4> their_frame{};
  for (std::size_t j = 0; j < 4; ++j) their_frame[j] = {dot(theirs[j], along), cross(along, theirs[j])};
  const double inverse = speed > 0.0 ? 1.0 / speed : 0.0;
  double closest = std::numeric_limits<double>::infinity();
  double at = 0.0;
  for (const vec2& p : mine) {
    const vec2 pf{dot(p, along), cross(along, p)};
    for (const vec2& q : their_frame) {
      const double y = pf.y - q.y;
      const double y2 = y * y;
      if (y2 >= closest) continue;
      const double x = pf.x - q.x;
      const double s = std::clamp(-x * inverse, 0.0, duration);
      const double dx = x + speed * s;
      const double squared = dx * dx + y2;
      if (squared < closest) {
        closest = squared;
        at = s;
      }
    }
  }
  translation_minimum best{std::sqrt(closest), at};
  if (separations.at(0.0) < best.distance) best = lower({corner_distance(a, b), 0.0}, best);
  if (separations.at(duration) < best.distance) {
    best = lower(best, {corner_distance(moved(a, duration * w), b), duration});
  }
  return best;
}

}  // namespace

translation_minimum smallest_signed_distance(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion, const translation_minimum& separation) {
  if (separation.distance + radius <= 0.0) return separation;
  return apart_minimum(a, centre, radius, motion);
}

namespace {

translation_minimum apart_minimum(const placed_rectangle& a, vec2 centre, double radius, const translation& motion) {
  const vec2 w = motion.velocity;
  translation_minimum best{signed_distance(a, centre, radius), 0.0};
  best = lower(best, {signed_distance(moved(a, motion.duration * w), centre, radius), motion.duration});
  double closest = std::numeric_limits<double>::infinity();
  double at = 0.0;
  for (const vec2& p : corners(a)) {
    const translation_minimum pair = closest_approach_squared(p - centre, w, motion.duration);
    if (pair.distance < closest) {
      closest = pair.distance;
      at = pair.time;
    }
  }
  if (const double corner = std::sqrt(closest) - radius; corner < best.distance) best = {corner, at};
  return best;
}

}  // namespace

translation_minimum smallest_signed_distance(const placed_footprint& a, const placed_footprint& b,
                                             const translation& motion) {
  const vec2 w = motion.velocity;
  const double duration = motion.duration;
  const double radii = a.radius + b.radius;
  // Separation along every edge normal of a polygon core: the projections of a move by (w·n) s.
  std::array<line, 4 * max_polygon_vertices> lines{};
  std::size_t count = 0;
  for (const placed_footprint* f : {&a, &b}) {
    if (f->vertex_count < 3) continue;
    for (std::size_t i = 0; i < f->vertex_count; ++i) {
      const vec2 edge = f->vertices[(i + 1) % f->vertex_count] - f->vertices[i];
      const double length = norm(edge);
      if (length == 0.0) continue;
      const vec2 n{-edge.y / length, edge.x / length};
      double a_lo = std::numeric_limits<double>::infinity();
      double a_hi = -a_lo;
      double b_lo = a_lo;
      double b_hi = -a_lo;
      for (std::size_t k = 0; k < a.vertex_count; ++k) {
        a_lo = std::min(a_lo, dot(a.vertices[k], n));
        a_hi = std::max(a_hi, dot(a.vertices[k], n));
      }
      for (std::size_t k = 0; k < b.vertex_count; ++k) {
        b_lo = std::min(b_lo, dot(b.vertices[k], n));
        b_hi = std::max(b_hi, dot(b.vertices[k], n));
      }
      const double q = dot(w, n);
      lines[count++] = {b_lo - a_hi, -q};
      lines[count++] = {a_lo - b_hi, q};
    }
  }
  if (count > 0) {
    const translation_minimum separation = lowest_on_envelope(lines.data(), count, duration);
    if (separation.distance <= 0.0) return {separation.distance - radii, separation.time};
  }
  translation_minimum best{signed_distance(a, b), 0.0};
  best = lower(best, {signed_distance(moved(a, duration * w), b), duration});
  double closest = std::numeric_limits<double>::infinity();
  double at = 0.0;
  for (std::size_t i = 0; i < a.vertex_count; ++i) {
    for (std::size_t j = 0; j < b.vertex_count; ++j) {
      const translation_minimum pair = closest_approach_squared(a.vertices[i] - b.vertices[j], w, duration);
      if (pair.distance < closest) {
        closest = pair.distance;
        at = pair.time;
      }
    }
  }
  if (const double corner = std::sqrt(closest) - radii; corner < best.distance) best = {corner, at};
  return best;
}

double first_contact(const placed_rectangle& a, const placed_rectangle& b, const translation& motion, double level) {
  return earliest_at_or_below([&](double s) { return signed_distance(moved(a, s * motion.velocity), b); },
                              smallest_signed_distance(a, b, motion), level);
}

double first_contact(const placed_rectangle& a, vec2 centre, double radius, const translation& motion, double level) {
  return earliest_at_or_below([&](double s) { return signed_distance(moved(a, s * motion.velocity), centre, radius); },
                              smallest_signed_distance(a, centre, radius, motion), level);
}

double first_contact(const placed_footprint& a, const placed_footprint& b, const translation& motion, double level) {
  return earliest_at_or_below([&](double s) { return signed_distance(moved(a, s * motion.velocity), b); },
                              smallest_signed_distance(a, b, motion), level);
}

}  // namespace mm
