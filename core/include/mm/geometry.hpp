#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mm {

/// A point or a vector in the plane [m]. World frame: x east, y north (spec §1).
struct vec2 {
  double x = 0.0;
  double y = 0.0;

  friend constexpr bool operator==(const vec2&, const vec2&) = default;
};

constexpr vec2 operator+(vec2 a, vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr vec2 operator-(vec2 a, vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr vec2 operator-(vec2 a) { return {-a.x, -a.y}; }
constexpr vec2 operator*(double k, vec2 a) { return {k * a.x, k * a.y}; }
constexpr vec2 operator*(vec2 a, double k) { return {k * a.x, k * a.y}; }

constexpr double dot(vec2 a, vec2 b) { return a.x * b.x + a.y * b.y; }
/// z-component of the 3-D cross product: positive when b is counter-clockwise of a.
constexpr double cross(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr double squared_norm(vec2 a) { return dot(a, a); }
inline double norm(vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }

/// Squared distance [m²] from `p` to the segment from `a` to `b` (a point when a = b).
inline double squared_distance_to_segment(vec2 p, vec2 a, vec2 b) {
  const vec2 ab = b - a;
  const double length2 = squared_norm(ab);
  const double t = length2 > 0.0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return squared_norm(p - (a + t * ab));
}

/// Unit vector of direction `angle` [rad], counter-clockwise from +x.
inline vec2 unit_vector(double angle) { return {std::cos(angle), std::sin(angle)}; }

/// `v` rotated counter-clockwise by the angle whose cosine is `c` and sine is `s`.
constexpr vec2 rotated(vec2 v, double c, double s) { return {c * v.x - s * v.y, s * v.x + c * v.y}; }

/// Pose of a road user: reference-point position [m] and heading [rad], counter-clockwise from +x.
struct pose {
  vec2 position;
  double heading = 0.0;

  friend bool operator==(const pose&, const pose&) = default;
};

/// `local` (a point in the frame of `frame`: x forward, y left) expressed in the world frame.
inline vec2 to_world(const pose& frame, vec2 local) {
  return frame.position + rotated(local, std::cos(frame.heading), std::sin(frame.heading));
}

/// The world point `world` expressed in the frame of `frame`.
inline vec2 to_local(const pose& frame, vec2 world) {
  return rotated(world - frame.position, std::cos(frame.heading), -std::sin(frame.heading));
}

/// `angle` [rad] wrapped to (−π, π].
double wrap_angle(double angle);

/// sin(x)/x, continuous at 0.
double sinc(double x);

/// (1 − cos x)/x, continuous at 0 (→ x/2).
double versine_ratio(double x);

}  // namespace mm
