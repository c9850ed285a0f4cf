#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm {

/// The motion of one placed footprint relative to another when both go straight at constant
/// velocities with fixed headings: a translation of the first at `velocity` (its velocity less the
/// other's) [m/s] for `duration` ≥ 0 [s]. After T_h the ego goes straight at the speed and heading
/// reached at T_h (spec §3), and after τ an obstacle goes straight at the velocity reached at τ
/// (spec §4): from max(T_h, τ) to T_c their relative motion is such a translation.
struct translation {
  vec2 velocity;
  double duration = 0.0;
};

/// The smallest signed distance of two footprints over a translation, and when it is reached.
struct translation_minimum {
  double distance = std::numeric_limits<double>::infinity();  ///< [m]
  double time = 0.0;  ///< [s] after the start of the translation, in [0, duration]
};

/// Smallest signed distance [m] of `a` (placed at the start, moving by `motion`) and the fixed `b`
/// over [0, duration], in continuous time, in closed form:
/// - The separation along the four face normals, max_n (|n·r(s)| − h_n) with r(s) = r₀ + w s the
///   centres' offset, is convex and piecewise linear in s; its lowest point is found on its upper
///   envelope. Where it is ≤ 0 the footprints overlap and it is their signed distance
///   (separating-axis theorem), so it is then the minimum.
/// - Otherwise the offset's path misses the Minkowski difference of the two rectangles, and the
///   smallest distance between a segment and a convex polygon is reached at an end of the segment
///   or at a vertex of the polygon: the distances at s = 0 and s = duration, and of every pair of
///   corners along the motion (the vertices of the difference are differences of corners).
translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion);

/// The same for a rectangle `a` and a fixed disc of `radius` [m] centred at `centre` [m].
translation_minimum smallest_signed_distance(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion);

/// A distance that grows linearly over a translation: `base` + `rate`·s [m] at time s.
struct widening {
  double base = 0.0;  ///< [m]
  double rate = 0.0;  ///< [m/s]
};

/// The first stage of `smallest_signed_distance` of two rectangles: the lowest point of their face
/// separation over the translation [m], a lower bound of the smallest signed distance, equal to it
/// when ≤ 0. With a `widening` w(s), the lowest point of the separation less w(s): a lower bound of
/// min_s (signed distance − w(s)), in the same closed form (the lines' offsets and slopes move).
translation_minimum smallest_face_separation(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const widening& less = {});
/// The same for a rectangle and a disc: the lowest point of the disc centre's separation from the
/// rectangle along its two axes, less the radius.
translation_minimum smallest_face_separation(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion, const widening& less = {});
/// The face separations of two footprints over a translation, prepared once for several tests:
/// along each face normal n, |p_n + q_n s| − h_n, with p_n the centres' offset, q_n its rate and h_n
/// the sum of the half extents (two rectangles: their four face normals; a rectangle and a disc:
/// the rectangle's two axes, the extents widened by the radius).
class face_separations {
 public:
  face_separations(const placed_rectangle& a, const placed_rectangle& b, const translation& motion);
  face_separations(const placed_rectangle& a, vec2 centre, double radius, const translation& motion);
  /// `face_separation_reaches` of the same arguments.
  bool reach(const widening& level) const;
  /// The same for a constant level [m]: each slab's interval of times from the reciprocal of its
  /// rate, kept for the next constant level.
  bool reach(double level) const;
  /// `smallest_face_separation` of the same arguments.
  translation_minimum lowest(const widening& less = {}) const;
  /// The face separation at time s [m]: a lower bound of the signed distance then.
  double at(double s) const;

 private:
  struct slab {
    double offset;       ///< p [m]
    double rate;         ///< q [m/s]
    double half_extent;  ///< h [m]
  };
  std::array<slab, 4> slabs_{};
  std::size_t count_;
  double duration_;
  mutable std::array<double, 4> inverse_rates_{};  ///< 1/q, where `inverted_`
  mutable bool inverted_ = false;
};

/// True when the face separation of `a` moved by `motion` and `b` is at most `level`(s) at some time
/// s ∈ [0, duration]: the slabs |n·r(s)| ≤ h_n + level(s) of the four face normals meet within
/// [0, duration] (a ray–box test, one division per slab side). What a threshold needs, without the
/// minimum.
bool face_separation_reaches(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                             const widening& level);
/// The same for a rectangle and a disc (`smallest_face_separation` of the two).
bool face_separation_reaches(const placed_rectangle& a, vec2 centre, double radius, const translation& motion,
                             const widening& level);
/// True when `smallest_signed_distance` ≤ `level` [m]: the slab tests, and the distance of the
/// ends and the corner pairs only when the footprints come within the level without overlapping.
bool signed_distance_reaches(const placed_rectangle& a, const placed_rectangle& b, const translation& motion,
                             double level);
bool signed_distance_reaches(const placed_rectangle& a, vec2 centre, double radius, const translation& motion,
                             double level);

/// `smallest_signed_distance` of two rectangles from their prepared face separations.
translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const face_separations& separations);

/// `smallest_signed_distance` from its first stage `separation` (`smallest_face_separation` of the
/// same arguments), bit for bit.
translation_minimum smallest_signed_distance(const placed_rectangle& a, const placed_rectangle& b,
                                             const translation& motion, const translation_minimum& separation);
translation_minimum smallest_signed_distance(const placed_rectangle& a, vec2 centre, double radius,
                                             const translation& motion, const translation_minimum& separation);

/// The same for any two placed footprints (convex cores, each a point or a polygon, widened by a
/// disc): the face normals of both polygons, and the vertices' pairs. The reference of the two
/// closed forms above, and what general shapes use.
translation_minimum smallest_signed_distance(const placed_footprint& a, const placed_footprint& b,
                                             const translation& motion);

/// min over s ∈ [0, duration] of |offset + velocity·s| − growth·s [m]: how close a point moving at
/// `velocity` [m/s] from `offset` [m] comes to the edge of a disc about the origin whose radius
/// grows at `growth` ≥ 0 [m/s]. Convex in s, so minimised in closed form: where the rate at which
/// the distance changes equals the growth, (offset + velocity·s)·velocity / |…| = growth, clamped.
double closest_approach_to_growing_disc(vec2 offset, vec2 velocity, double growth, double duration);

/// `a` moved by `displacement` [m].
placed_rectangle moved(const placed_rectangle& a, vec2 displacement);
placed_footprint moved(const placed_footprint& a, vec2 displacement);

/// Earliest time s ∈ [0, duration] [s] at which the signed distance of `a` moved by `motion` and `b`
/// is ≤ `level` [m], or +∞ when it stays above. The signed distance is convex along a translation
/// (the signed distance to a convex set is convex), so it is non-increasing up to its minimum: the
/// crossing is found by bisection of `signed_distance` between 0 and the minimum's time, to 1e-9 s.
double first_contact(const placed_rectangle& a, const placed_rectangle& b, const translation& motion, double level);
double first_contact(const placed_rectangle& a, vec2 centre, double radius, const translation& motion, double level);
double first_contact(const placed_footprint& a, const placed_footprint& b, const translation& motion, double level);

}  // namespace mm
