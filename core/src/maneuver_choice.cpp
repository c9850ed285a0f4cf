#include "mm/maneuver_choice.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "mm/forecast_policy.hpp"

namespace mm {

std::string_view to_string(planning_mode mode) {
  switch (mode) {
    case planning_mode::nominal: return "nominal";
    case planning_mode::avoid: return "avoid";
    case planning_mode::urgent: return "urgent";
    case planning_mode::near_crash: return "near_crash";
  }
  return "unknown";
}

double maneuver_effort(const maneuver& u, const maneuver& nominal, double initial_speed, const effort_weights& weights) {
  const double longitudinal = u.acceleration - nominal.acceleration;
  const double lateral = initial_speed * initial_speed * (u.curvature - nominal.curvature);
  return weights.longitudinal * longitudinal * longitudinal + weights.lateral * lateral * lateral;
}

namespace {

/// Ranking of a candidate: effort first (least, or most when `maximal`), then the smaller
/// steering change, then the smaller acceleration change; ties within `tie_tolerance`.
struct candidate_rank {
  double effort;
  double steering_change;
  double acceleration_change;

  bool better_than(const candidate_rank& other, bool maximal) const {
    const double sign = maximal ? -1.0 : 1.0;
    if (std::abs(effort - other.effort) > tie_tolerance * (1.0 + std::abs(effort))) {
      return sign * effort < sign * other.effort;
    }
    if (std::abs(steering_change - other.steering_change) > tie_tolerance) return steering_change < other.steering_change;
    return acceleration_change < other.acceleration_change - tie_tolerance;
  }
};

/// The verified safe candidate of `f` with the least (or, `maximal`, the largest) effort.
std::optional<std::size_t> extreme_effort_candidate(const choice_input& in, family f, bool maximal) {
  std::vector<std::pair<candidate_rank, std::size_t>> ranked;
  for (const index_range r : {in.samples->grid(f), in.samples->nominal_column(f)}) {
    for (std::size_t m = r.begin; m < r.end; ++m) {
      if (in.colliding->test(m)) continue;
      const maneuver& u = in.samples->maneuvers[m];
      ranked.push_back({{maneuver_effort(u, in.nominal, in.initial_speed, in.weights),
                         std::abs(u.curvature - in.nominal.curvature),
                         std::abs(u.acceleration - in.nominal.acceleration)},
                        m});
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [&](const auto& x, const auto& y) { return x.first.better_than(y.first, maximal); });
  for (const auto& [rank, m] : ranked) {
    if (!in.verify || in.verify(in.samples->maneuvers[m])) return m;
  }
  return std::nullopt;
}

family other(family f) { return f == family::brake ? family::accelerate : family::brake; }

}  // namespace

std::optional<maneuver_decision> choose_maneuver(const choice_input& in) {
  if (in.nominal_safe) return maneuver_decision{in.nominal, planning_mode::nominal, std::nullopt};
  bool urgent = false;
  if (in.urgent_steering) {
    urgent = true;
    for (const family f : {family::brake, family::accelerate}) {
      const index_range column = in.samples->nominal_column(f);
      if (!in.colliding->all_in(column.begin, column.end)) urgent = false;
    }
  }
  for (const family f : {in.selected_family, other(in.selected_family)}) {
    if (const auto m = extreme_effort_candidate(in, f, urgent)) {
      return maneuver_decision{in.samples->maneuvers[*m], urgent ? planning_mode::urgent : planning_mode::avoid, *m};
    }
  }
  return std::nullopt;
}

maneuver_decision near_crash_maneuver(const maneuver_samples& samples, std::span<const double> first_collision,
                                      std::span<const double> first_contact, double nominal_curvature) {
  std::size_t best = 0;
  const auto steering_change = [&](std::size_t m) { return std::abs(samples.maneuvers[m].curvature - nominal_curvature); };
  for (std::size_t m = 1; m < samples.size(); ++m) {
    const maneuver& u = samples.maneuvers[m];
    const maneuver& b = samples.maneuvers[best];
    if (first_collision[m] != first_collision[best]) {
      if (first_collision[m] > first_collision[best]) best = m;
    } else if (u.acceleration != b.acceleration) {
      if (u.acceleration < b.acceleration) best = m;
    } else if (first_contact[m] != first_contact[best]) {
      if (first_contact[m] > first_contact[best]) best = m;
    } else if (steering_change(m) < steering_change(best) - tie_tolerance) {
      best = m;
    }
  }
  return {samples.maneuvers[best], planning_mode::near_crash, best};
}

}  // namespace mm
