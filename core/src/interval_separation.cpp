#include "mm/interval_separation.hpp"

#include <algorithm>
#include <cmath>

namespace mm {

namespace {

double support(const support_shape& shape, vec2 n, vec2 heading) {
  return shape.half.x * std::abs(dot(n, heading)) + shape.half.y * std::abs(cross(n, heading)) + shape.radius;
}

}  // namespace

interval_separation separated_throughout(const support_shape& a, const interval_motion& motion_a, const support_shape& b,
                                         const interval_motion& motion_b, double duration, double margin,
                                         std::uint8_t first_direction) {
  constexpr std::uint8_t directions = 5;
  const double corner_a = norm(a.half);
  const double corner_b = norm(b.half);
  const double dip = (duration * duration * (motion_a.acceleration + motion_b.acceleration) +
                      corner_a * motion_a.turn * motion_a.turn + corner_b * motion_b.turn * motion_b.turn) /
                         8.0 +
                     corner_a * motion_a.bend + corner_b * motion_b.bend;
  // Far above the rounding of the few operations below.
  const double needed = margin + dip * (1.0 + 1e-9) + 1e-9;
  const vec2 apart_start = motion_b.start.position - motion_a.start.position;
  const vec2 apart_end = motion_b.end.position - motion_a.end.position;
  interval_separation result;
  const auto separates = [&](vec2 n) {
    const double at_start = dot(n, apart_start);
    const double side = at_start < 0.0 ? -1.0 : 1.0;
    const double gap_end =
        side * dot(n, apart_end) - support(a, n, motion_a.end.direction) - support(b, n, motion_b.end.direction);
    if (!(gap_end > needed)) return false;
    const double gap_start =
        side * at_start - support(a, n, motion_a.start.direction) - support(b, n, motion_b.start.direction);
    if (!(gap_start > needed)) return false;
    result.separated = true;
    result.gap_at_end = gap_end - margin - 1e-12;
    return true;
  };
  const auto direction = [&](std::uint8_t index) -> vec2 {
    switch (index) {
      case 0: return motion_a.start.direction;
      case 1: return {-motion_a.start.direction.y, motion_a.start.direction.x};
      case 2: return motion_b.start.direction;
      case 3: return {-motion_b.start.direction.y, motion_b.start.direction.x};
      default: {
        const double length = norm(apart_start);
        return length > 0.0 ? (1.0 / length) * apart_start : vec2{0.0, 0.0};
      }
    }
  };
  // A disc's axes are no better than any other direction: bit i of `tried_directions` says whether
  // direction i is tried.
  unsigned tried_directions = 0b11111U;
  if (a.half.x == 0.0 && a.half.y == 0.0) tried_directions &= ~0b00011U;
  if (b.half.x == 0.0 && b.half.y == 0.0) tried_directions &= ~0b01100U;
  unsigned index = first_direction % directions;
  for (unsigned tried = 0; tried < directions; ++tried, index = index + 1 == directions ? 0 : index + 1) {
    if (((tried_directions >> index) & 1U) == 0) continue;
    if (separates(direction(static_cast<std::uint8_t>(index)))) {
      result.direction = static_cast<std::uint8_t>(index);
      return result;
    }
  }
  return result;
}

}  // namespace mm
