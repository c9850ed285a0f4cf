#include "mm/sim/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mm::sim {

std::string_view to_string(bypass_side side) {
  switch (side) {
    case bypass_side::none: return "none";
    case bypass_side::left: return "left";
    case bypass_side::right: return "right";
  }
  return "unknown";
}

std::optional<double> constant_velocity_ttc(const mm::footprint& a, const mm::pose& pose_a, vec2 velocity_a,
                                            const mm::footprint& b, const mm::pose& pose_b, vec2 velocity_b) {
  const auto placed_a = [&](double t) {
    return mm::place(a, {pose_a.position + t * velocity_a, pose_a.heading});
  };
  const auto placed_b = [&](double t) {
    return mm::place(b, {pose_b.position + t * velocity_b, pose_b.heading});
  };
  const auto touching = [&](double t) { return mm::overlaps(placed_a(t), placed_b(t)); };
  const auto gap = [&](double t) { return mm::gap_distance(placed_a(t), placed_b(t)); };
  if (touching(0.0)) return 0.0;

  // Contact needs the reference points within the sum of the bounding radii; under relative
  // uniform motion that can only happen before t* + (R_a + R_b)/|v|, t* the closest approach.
  const vec2 separation = pose_b.position - pose_a.position;
  const vec2 relative = velocity_b - velocity_a;
  const double speed2 = squared_norm(relative);
  if (speed2 == 0.0) return std::nullopt;
  const double reach = mm::bounding_radius(a) + mm::bounding_radius(b);
  const double closest = std::max(0.0, -dot(separation, relative) / speed2);
  double lo = 0.0;
  double hi = closest + reach / std::sqrt(speed2);

  // Golden-section search for the minimum of the convex gap on [lo, hi].
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - ratio * (hi - lo);
  double x2 = lo + ratio * (hi - lo);
  double g1 = gap(x1);
  double g2 = gap(x2);
  double t_min = hi;
  for (int i = 0; i < 200 && hi - lo > 1e-9; ++i) {
    if (g1 == 0.0) {
      t_min = x1;
      break;
    }
    if (g2 == 0.0) {
      t_min = x2;
      break;
    }
    if (g1 < g2) {
      hi = x2;
      x2 = x1;
      g2 = g1;
      x1 = hi - ratio * (hi - lo);
      g1 = gap(x1);
    } else {
      lo = x1;
      x1 = x2;
      g1 = g2;
      x2 = lo + ratio * (hi - lo);
      g2 = gap(x2);
    }
    t_min = 0.5 * (lo + hi);
  }
  if (!touching(t_min)) {
    // The minimum may be a touching point (gap 0 without overlap) or a miss.
    if (gap(t_min) > 1e-9) return std::nullopt;
    // Grazing contact: the overlap, if any, is within numerical noise of t_min.
    return t_min;
  }
  // First overlap on [0, t_min] by bisection: no overlap at `free`, overlap at `hit`.
  double free = 0.0;
  double hit = t_min;
  while (hit - free > 1e-6) {
    const double mid = 0.5 * (free + hit);
    (touching(mid) ? hit : free) = mid;
  }
  return hit;
}

double quantile(std::span<const double> values, double q) {
  if (values.empty()) return 0.0;
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  if (q == 0.5 && n % 2 == 0) return 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  return sorted[std::clamp<std::size_t>(rank, 1, n) - 1];
}

}  // namespace mm::sim
