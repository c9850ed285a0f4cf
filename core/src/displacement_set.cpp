#include "mm/displacement_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mm {
namespace {

/// (x − sin x)/x³, continuous at 0.
double cubic_sine_defect(double x) {
  const double x2 = x * x;
  if (std::abs(x) < 1e-2) return 1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0;
  return (x - std::sin(x)) / (x2 * x);
}

/// ∫_{κ0}^{κ1} [G(s1, κ) − G(s0, κ)] dκ by 4-point Gauss–Legendre (the integrand is smooth).
double cell_area(double s0, double s1, double kappa0, double kappa1) {
  static constexpr std::array<double, 4> nodes{-0.8611363115940526, -0.3399810435848563,
                                               0.3399810435848563, 0.8611363115940526};
  static constexpr std::array<double, 4> weights{0.3478548451374538, 0.6521451548625461,
                                                 0.6521451548625461, 0.3478548451374538};
  const double mid = 0.5 * (kappa0 + kappa1);
  const double half = 0.5 * (kappa1 - kappa0);
  double sum = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double kappa = mid + half * nodes[i];
    sum += weights[i] * (area_element_primitive(s1, kappa) - area_element_primitive(s0, kappa));
  }
  return sum * half;
}

/// Node `i` of `count` nodes spread evenly over [lo, hi], and the bounds of its cell.
struct node_cell {
  double node;
  double lo;
  double hi;
};

node_cell node_and_cell(double lo, double hi, std::size_t i, std::size_t count) {
  if (count == 1) return {0.5 * (lo + hi), lo, hi};
  const double step = (hi - lo) / static_cast<double>(count - 1);
  const double node = i + 1 == count ? hi : lo + step * static_cast<double>(i);
  return {node, std::max(lo, node - step / 2.0), std::min(hi, node + step / 2.0)};
}

}  // namespace

std::string_view to_string(family f) { return f == family::brake ? "brake" : "accelerate"; }

double area_element(double arc_length, double curvature) {
  // (1 − cos x)/κ² with x = κs equals s²·sinc(x/2)²/2.
  const double half_sinc = sinc(curvature * arc_length / 2.0);
  return 0.5 * arc_length * arc_length * half_sinc * half_sinc;
}

double area_element_primitive(double arc_length, double curvature) {
  return arc_length * arc_length * arc_length * cubic_sine_defect(curvature * arc_length);
}

displacement_set available_displacements(double initial_speed, const ego_limits& limits,
                                         double horizon, family fam,
                                         const sampling_resolution& resolution) {
  displacement_set set;
  set.fam = fam;
  set.min_acceleration = fam == family::brake ? -limits.max_deceleration : 0.0;
  set.max_acceleration = fam == family::brake ? 0.0 : limits.max_acceleration;
  set.max_curvature = max_curvature(initial_speed, limits);
  set.acceleration_count = resolution.accelerations;
  set.curvature_count = set.max_curvature > 0.0 ? resolution.curvatures : 1;
  set.samples.reserve(set.acceleration_count * set.curvature_count);

  const auto distance = [&](double a) {
    return travelled_distance(initial_speed, a, horizon, limits.speed_cap);
  };
  for (std::size_t ia = 0; ia < set.acceleration_count; ++ia) {
    const node_cell a = node_and_cell(set.min_acceleration, set.max_acceleration, ia, set.acceleration_count);
    const double s = distance(a.node);
    const double s0 = distance(a.lo);
    const double s1 = distance(a.hi);
    for (std::size_t ik = 0; ik < set.curvature_count; ++ik) {
      const node_cell k = node_and_cell(-set.max_curvature, set.max_curvature, ik, set.curvature_count);
      const double weight = set.max_curvature > 0.0
                                ? cell_area(s0, s1, k.lo, k.hi)
                                : area_element_primitive(s1, 0.0) - area_element_primitive(s0, 0.0);
      set.samples.push_back({{a.node, k.node}, arc_point(k.node, s), std::max(weight, 0.0)});
      set.area += set.samples.back().area_weight;
    }
  }
  const std::size_t kappa_cells = set.curvature_count > 1 ? set.curvature_count - 1 : 1;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    const double s0 = distance(set.samples[ia * set.curvature_count].u.acceleration);
    const double s1 = distance(set.samples[(ia + 1) * set.curvature_count].u.acceleration);
    for (std::size_t ik = 0; ik < kappa_cells; ++ik) {
      double weight = 0.0;
      if (set.max_curvature <= 0.0) {
        weight = area_element_primitive(s1, 0.0) - area_element_primitive(s0, 0.0);
      } else if (set.curvature_count == 1) {
        weight = cell_area(s0, s1, -set.max_curvature, set.max_curvature);
      } else {
        weight = cell_area(s0, s1, set.samples[ik].u.curvature, set.samples[ik + 1].u.curvature);
      }
      set.cell_weights.push_back(std::max(weight, 0.0));
    }
  }
  constexpr double degenerate_area = 1e-12;
  if (set.area <= degenerate_area) {
    set.degenerate = true;
    set.area = 0.0;
    const double equal = 1.0 / static_cast<double>(set.samples.size());
    for (displacement_sample& sample : set.samples) sample.area_weight = equal;
  }
  return set;
}

}  // namespace mm
