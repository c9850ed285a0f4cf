#include "mm/maneuver_choice.hpp"

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

/// The safe candidate of `f` with the least (or, `maximal`, the largest) effort.
std::optional<std::size_t> extreme_effort_candidate(const choice_input& in, family f, bool maximal) {
  std::optional<std::size_t> best;
  double best_effort = 0.0;
  for (const index_range r : {in.samples->grid(f), in.samples->nominal_column(f)}) {
    for (std::size_t m = r.begin; m < r.end; ++m) {
      if (in.colliding->test(m)) continue;
      const double effort = maneuver_effort(in.samples->maneuvers[m], in.nominal, in.initial_speed, in.weights);
      if (!best || (maximal ? effort > best_effort : effort < best_effort)) {
        best = m;
        best_effort = effort;
      }
    }
  }
  return best;
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

maneuver_decision near_crash_maneuver(const maneuver_samples& samples, std::span<const double> first_collision) {
  std::size_t best = 0;
  for (std::size_t m = 1; m < samples.size(); ++m) {
    const bool later = first_collision[m] > first_collision[best];
    const bool as_late_braking_harder = first_collision[m] == first_collision[best] &&
                                        samples.maneuvers[m].acceleration < samples.maneuvers[best].acceleration;
    if (later || as_late_braking_harder) best = m;
  }
  return {samples.maneuvers[best], planning_mode::near_crash, best};
}

}  // namespace mm
