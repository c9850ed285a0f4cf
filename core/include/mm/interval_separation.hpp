#pragma once

#include <cstdint>
#include <limits>

#include "mm/geometry.hpp"
#include "mm/maneuver.hpp"

namespace mm {

/// The support of a footprint along a unit direction n: h(n) = half.x |n·d| + half.y |n·d⊥| +
/// radius [m], d its heading direction. A rectangle has radius 0, a disc half (0, 0). As a function
/// of the heading angle ψ, h'' ≥ −|half| (between its kinks h'' = −(h − radius); the kinks are convex).
struct support_shape {
  vec2 half;            ///< half length and half width of the core rectangle [m]
  double radius = 0.0;  ///< of the disc it is inflated by [m]
};

/// How a footprint moves over an interval [t_a, t_b]: its placements at both ends and two bounds.
struct interval_motion {
  placement start;      ///< at t_a
  placement end;        ///< at t_b
  double acceleration;  ///< |p''| of the reference point over the interval [m/s²] (p continuously differentiable)
  double turn;          ///< how far the heading turns over the interval [rad], always the same way
  /// How far the heading departs from its linear interpolation in time over the interval [rad]:
  /// 0 for a constant turn rate, |κ|·|a|·Δt²/8 on an arc of curvature κ driven with acceleration
  /// a (the arc length's departure from its chord times κ), `turn` where the turn rate jumps.
  double bend = 0.0;
};

/// Whether one fixed direction separates two moving footprints throughout an interval.
struct interval_separation {
  bool separated = false;
  /// Their gap along the separating direction at t_b less the margin [m], a lower bound of their
  /// signed distance − margin there; −∞ when not separated.
  double gap_at_end = -std::numeric_limits<double>::infinity();
  /// The separating direction: 0 and 1 the first footprint's heading and its normal at t_a, 2 and 3
  /// the second's, 4 the line of their reference points at t_a.
  std::uint8_t direction = 0;
};

/// True when some fixed unit direction n separates footprint a and footprint b by more than
/// `margin` [m] at every time of an interval of `duration` [s] (then their signed distance stays
/// above the margin: docs/method.md §4.4). Along n the gap is g = σ n·(p_b − p_a) − h_a(n) − h_b(n),
/// σ the side b is on at t_a. The first term is C¹ with second derivative at most
/// A = |p_a''| + |p_b''|, so it stays above its chord in time less A·Δt²/8. A support h(ψ), ψ the
/// heading, has h'' ≥ −|half| (its kinks are convex), so it stays below its chord in ψ plus
/// |half|·Δψ²/8, and that chord departs from the chord in time by at most |half|·`bend` (h is
/// |half|-Lipschitz in ψ). So g stays above the smaller of its two ends less the sum of these dips.
/// The directions tried, from `first_direction` on (the one that separated the interval before
/// usually separates the next): both footprints' axes at t_a and the line of their reference points
/// there; the first that separates is returned.
interval_separation separated_throughout(const support_shape& a, const interval_motion& motion_a, const support_shape& b,
                                         const interval_motion& motion_b, double duration, double margin,
                                         std::uint8_t first_direction = 4);

}  // namespace mm
