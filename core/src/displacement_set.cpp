#include "mm/displacement_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace mm {
namespace {

/// (x − sin x)/x³, continuous at 0. For |x| ≤ 1.5 its Taylor series Σ (−x²)ⁿ/(2n + 3)! to n = 9
/// (the next term is below 3·10⁻¹⁷ of the sum): no cancellation, and no sine; beyond, the formula.
double cubic_sine_defect(double x) {
  const double x2 = x * x;
  if (std::abs(x) <= 1.5) {
    // Horner in −x² with the coefficients 1/(2n + 3)!, n = 9 down to 0.
    constexpr std::array<double, 10> inverse_factorials{
        1.0 / 51090942171709440000.0, 1.0 / 121645100408832000.0, 1.0 / 355687428096000.0, 1.0 / 1307674368000.0,
        1.0 / 6227020800.0,           1.0 / 39916800.0,           1.0 / 362880.0,           1.0 / 5040.0,
        1.0 / 120.0,                  1.0 / 6.0};
    double sum = 0.0;
    for (const double c : inverse_factorials) sum = c - x2 * sum;
    return sum;
  }
  return (x - std::sin(x)) / (x2 * x);
}

/// 4-point Gauss–Legendre on [−1, 1].
constexpr std::array<double, 4> quadrature_nodes{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                                 0.8611363115940526};
constexpr std::array<double, 4> quadrature_weights{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                   0.3478548451374538};

/// ∫_{κ0}^{κ1} [G(s1, κ) − G(s0, κ)] dκ by 4-point Gauss–Legendre (the integrand is smooth).
double cell_area(double s0, double s1, double kappa0, double kappa1) {
  const double mid = 0.5 * (kappa0 + kappa1);
  const double half = 0.5 * (kappa1 - kappa0);
  double sum = 0.0;
  for (std::size_t i = 0; i < quadrature_nodes.size(); ++i) {
    const double kappa = mid + half * quadrature_nodes[i];
    sum += quadrature_weights[i] * (area_element_primitive(s1, kappa) - area_element_primitive(s0, kappa));
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

/// The acceleration [m/s²] in [lo, hi] whose arc length at the horizon T is s [m], from speed v0
/// in (0, cap]: `travelled_distance` inverted piece by piece. Stopping before T (|a| ≥ v0/T, s ≤
/// v0·T/2): s = v0²/(2|a|); reaching the cap before T (s ≥ v0·T + (cap − v0)·T/2): s = cap·T −
/// (cap − v0)²/(2a); else s = v0·T + a·T²/2.
double acceleration_for_arc_length(double s, double v0, double horizon, double cap, double lo, double hi) {
  const double t = horizon;
  double a = 0.0;
  if (s <= 0.5 * v0 * t) {
    a = -v0 * v0 / (2.0 * s);
  } else if (s >= v0 * t + 0.5 * (cap - v0) * t) {
    a = (cap - v0) * (cap - v0) / (2.0 * (cap * t - s));
  } else {
    a = 2.0 * (s - v0 * t) / (t * t);
  }
  return std::clamp(a, lo, hi);
}

/// True when rows evenly spaced in the arc length at the horizon T differ from rows evenly spaced
/// in a over [lo, hi]: from a speed in (0, cap], some acceleration of the range stops the ego or
/// reaches the cap within T, so s is not affine in a (outside `travelled_distance`'s one-piece
/// case, with its slack).
bool arc_length_has_a_kink(double v0, double horizon, double cap, double lo, double hi) {
  if (!(v0 > 0.0 && v0 <= cap)) return false;
  const auto inside = [&](double a) {
    const double end = v0 + a * horizon;
    const double slack = 1e-9 * (cap + std::abs(a) * horizon);
    return a == 0.0 || (end > slack && end < cap - slack);
  };
  return !inside(lo) || !inside(hi);
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

double evenly_spaced_acceleration(const displacement_set& set, std::size_t row) {
  return node_and_cell(set.min_acceleration, set.max_acceleration, row, set.acceleration_count).node;
}

displacement_set available_displacements(double initial_speed, const ego_limits& limits,
                                         double horizon, family fam,
                                         const sampling_resolution& resolution, bool node_weights,
                                         bool end_points) {
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
  // The rows are evenly spaced in the arc length at T_h, whose density carries the area (s²/2 per
  // unit of s when straight): evenly spaced in a, the rows of a slow ego's braking family would
  // crowd where it stops early, a sliver of the set. Where s is affine in a (no stop, no cap
  // within T_h) the two spacings are the same rows, computed in a.
  const double cap = limits.speed_cap;
  const bool by_arc_length = set.acceleration_count >= 3 &&
                             arc_length_has_a_kink(initial_speed, horizon, cap, set.min_acceleration, set.max_acceleration);
  const double s_min = by_arc_length ? distance(set.min_acceleration) : 0.0;
  const double s_max = by_arc_length ? distance(set.max_acceleration) : 0.0;
  const auto to_acceleration = [&](double arc_length) {
    if (arc_length <= s_min) return set.min_acceleration;
    if (arc_length >= s_max) return set.max_acceleration;
    return acceleration_for_arc_length(arc_length, initial_speed, horizon, cap, set.min_acceleration,
                                       set.max_acceleration);
  };
  const auto row_of = [&](std::size_t ia) {
    if (!by_arc_length) return node_and_cell(set.min_acceleration, set.max_acceleration, ia, set.acceleration_count);
    const node_cell s = node_and_cell(s_min, s_max, ia, set.acceleration_count);
    return node_cell{to_acceleration(s.node), to_acceleration(s.lo), to_acceleration(s.hi)};
  };
  std::vector<double> row_arc_lengths;  // s at T_h of each acceleration node
  row_arc_lengths.reserve(set.acceleration_count);
  for (std::size_t ia = 0; ia < set.acceleration_count; ++ia) {
    const node_cell a = row_of(ia);
    const double s = distance(a.node);
    row_arc_lengths.push_back(s);
    const double s0 = node_weights ? distance(a.lo) : 0.0;
    const double s1 = node_weights ? distance(a.hi) : 0.0;
    for (std::size_t ik = 0; ik < set.curvature_count; ++ik) {
      const node_cell k = node_and_cell(-set.max_curvature, set.max_curvature, ik, set.curvature_count);
      const double weight = !node_weights            ? 0.0
                            : set.max_curvature > 0.0 ? cell_area(s0, s1, k.lo, k.hi)
                                                      : area_element_primitive(s1, 0.0) - area_element_primitive(s0, 0.0);
      set.samples.push_back({{a.node, k.node}, end_points ? arc_point(k.node, s) : vec2{}, std::max(weight, 0.0)});
      set.area += set.samples.back().area_weight;
    }
  }
  const std::size_t kappa_cells = set.curvature_count > 1 ? set.curvature_count - 1 : 1;
  // G(s, κ) at the quadrature points of every κ cell, for the arc length of each acceleration
  // node: rows of cells share them (`cell_area` on the same values, computed once per row).
  const std::size_t nodes = quadrature_nodes.size();
  std::vector<double> kappas;  // [cell · nodes + q]
  std::vector<double> halves;  // [cell]
  if (set.max_curvature > 0.0) {
    kappas.reserve(kappa_cells * nodes);
    for (std::size_t ik = 0; ik < kappa_cells; ++ik) {
      const double kappa0 = set.curvature_count == 1 ? -set.max_curvature : set.samples[ik].u.curvature;
      const double kappa1 = set.curvature_count == 1 ? set.max_curvature : set.samples[ik + 1].u.curvature;
      const double mid = 0.5 * (kappa0 + kappa1);
      const double half = 0.5 * (kappa1 - kappa0);
      halves.push_back(half);
      for (const double node : quadrature_nodes) kappas.push_back(mid + half * node);
    }
  }
  // G is even in κ and the curvature nodes are symmetric about 0, so the cells mirrored about the
  // middle have the same weights: only the first half of the cells (and a middle one) is integrated.
  const std::size_t integrated = set.max_curvature > 0.0 ? (kappa_cells + 1) / 2 : kappa_cells;
  const auto primitives = [&](std::size_t ia, std::vector<double>& g) {
    const double s = row_arc_lengths[ia];
    g.clear();
    if (set.max_curvature <= 0.0) {
      g.assign(kappa_cells, area_element_primitive(s, 0.0));
      return;
    }
    for (std::size_t j = 0; j < integrated * nodes; ++j) g.push_back(area_element_primitive(s, kappas[j]));
  };
  std::vector<double> lower;
  std::vector<double> upper;
  lower.reserve(kappa_cells * nodes);
  upper.reserve(kappa_cells * nodes);
  if (set.acceleration_count > 1) primitives(0, lower);
  set.cell_weights.reserve((set.acceleration_count > 0 ? set.acceleration_count - 1 : 0) * kappa_cells);
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    primitives(ia + 1, upper);
    const std::size_t row = set.cell_weights.size();
    for (std::size_t ik = 0; ik < kappa_cells; ++ik) {
      if (ik >= integrated) {
        set.cell_weights.push_back(set.cell_weights[row + (kappa_cells - 1 - ik)]);
        continue;
      }
      double weight = 0.0;
      if (set.max_curvature <= 0.0) {
        weight = upper[ik] - lower[ik];
      } else {
        double sum = 0.0;
        for (std::size_t q = 0; q < nodes; ++q) {
          const std::size_t at = ik * nodes + q;
          sum += quadrature_weights[q] * (upper[at] - lower[at]);
        }
        weight = sum * halves[ik];
      }
      set.cell_weights.push_back(std::max(weight, 0.0));
    }
    std::swap(lower, upper);
  }
  if (!node_weights) {
    for (const double w : set.cell_weights) set.area += w;
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
