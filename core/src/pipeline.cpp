#include "pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "mm/assignment_search.hpp"
#include "mm/collision_sets.hpp"
#include "mm/maneuverability.hpp"

namespace mm::detail {
namespace {

/// True when the obstacle can come within reach of any maneuver within T_c (spec §9): the ego's
/// farthest travel plus the obstacle's, plus both bounding radii and the margin.
bool can_interact(const ego_state& ego, const forecast_obstacle& obstacle, const planner_config& config) {
  const double ego_travel =
      travelled_distance(ego.speed, ego.limits.max_acceleration, config.displacement_horizon, ego.limits.speed_cap) +
      speed_after(ego.speed, ego.limits.max_acceleration, config.displacement_horizon, ego.limits.speed_cap) *
          (config.collision_window - config.displacement_horizon);
  const double obstacle_travel = obstacle.motion.speed * config.collision_window;
  const double reach = ego_travel + obstacle_travel + bounding_radius(ego.shape) +
                       bounding_radius(obstacle.shape) + config.safety_margin;
  return squared_norm(obstacle.motion.pose.position - ego.pose.position) < reach * reach;
}

plan_result invalid(std::string error) {
  plan_result result;
  result.status = plan_status::invalid_input;
  result.error = std::move(error);
  return result;
}

/// Clearances of each relevant obstacle [j][i][m], and how to turn them into indices.
class evaluator {
 public:
  evaluator(const maneuver_samples& samples, bool reference) : samples_(samples), reference_(reference) {}

  /// Sample-wise minimum: the clearance with every obstacle of the list at once (union of [CSS]).
  clearance_set combined(std::span<const clearance_set* const> parts) const {
    clearance_set c(samples_.size(), std::numeric_limits<double>::infinity());
    for (const clearance_set* part : parts) {
      for (std::size_t m = 0; m < c.size(); ++m) c[m] = std::min(c[m], (*part)[m]);
    }
    return c;
  }

  /// MI− and MI+ (spec §6): the reference counts safe samples' areas; the fast path interpolates.
  maneuverability_pair indices(const clearance_set& c) const {
    if (reference_) return maneuverability_indices(samples_, colliding(c));
    const index_range b = samples_.grid(family::brake);
    const index_range a = samples_.grid(family::accelerate);
    return {maneuverability_index(samples_.brake, std::span(c).subspan(b.begin, b.size())),
            maneuverability_index(samples_.accelerate, std::span(c).subspan(a.begin, a.size()))};
  }

  double room(const clearance_set& c) const {
    const maneuverability_pair mi = indices(c);
    return std::max(mi.brake, mi.accelerate);
  }

  sample_mask colliding(const clearance_set& c) const {
    sample_mask mask(samples_.size());
    for (std::size_t m = 0; m < c.size(); ++m) {
      if (!(c[m] > 0.0)) mask.set(m);
    }
    return mask;
  }

 private:
  const maneuver_samples& samples_;
  bool reference_;
};

}  // namespace

plan_result run_pipeline(const plan_input& in, const pipeline_options& options) {
  if (auto error = validation_error(in)) return invalid(std::move(*error));
  const planner_config& config = in.config;
  const ego_state& ego = in.ego;
  const std::vector<double> taus = forecast_times(config);
  const std::size_t tau_count = taus.size();

  plan_result result;
  result.forecast_times = taus;
  const maneuver nominal = clamp_to_limits(in.nominal, ego.speed, ego.limits);

  // Obstacles: estimate, keep those that can interact (the others cost nothing, spec §9).
  std::vector<forecast_obstacle> relevant;
  std::vector<std::size_t> relevant_track;
  for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
    const obstacle_track& track = in.obstacles[j];
    obstacle_assessment assessment;
    assessment.id = track.id;
    assessment.motion = estimate_motion(track, config.history_window, in.time);
    assessment.time_to_collision = no_collision;
    const forecast_obstacle obstacle{assessment.motion, track.shape};
    assessment.relevant = can_interact(ego, obstacle, config);
    if (assessment.relevant) {
      relevant.push_back(obstacle);
      relevant_track.push_back(j);
    }
    result.obstacles.push_back(assessment);
  }
  const std::size_t n = relevant.size();

  collision_window window{config.displacement_horizon, config.collision_window, options.max_time_step,
                          config.safety_margin};
  for (const forecast_obstacle& o : relevant) {
    window.time_step = std::min(window.time_step, tunneling_time_step(ego, o, window));
  }
  window.time_step = std::min(window.time_step, config.collision_window);
  result.collision_time_step = window.time_step;

  const maneuver_samples samples = sample_maneuvers(ego, nominal.curvature, config.displacement_horizon, options.resolution);
  const evaluator evaluate(samples, options.reference);

  // Clearances per obstacle and forecast time (spec §5), and TTC (spec §6).
  std::vector<std::vector<clearance_set>> clearance(n);
  std::vector<double> ttc(n, no_collision);
  {
    std::optional<ego_sweep> sweep;
    if (!options.reference && n > 0) sweep.emplace(ego, samples, window);
    for (std::size_t j = 0; j < n; ++j) {
      if (options.reference) {
        for (const sample_mask& mask : collision_sets_reference(ego, samples, relevant[j], taus, window, options.proof_resolution)) {
          clearance_set c(samples.size());
          for (std::size_t m = 0; m < c.size(); ++m) c[m] = mask.test(m) ? -1.0 : 1.0;
          clearance[j].push_back(std::move(c));
        }
      } else {
        clearance[j] = clearances(*sweep, relevant[j], taus, clearance_cap);
      }
      ttc[j] = time_to_collision(ego, nominal, relevant[j], window);
      result.obstacles[relevant_track[j]].time_to_collision = ttc[j];
    }
  }
  result.time_to_collision = n == 0 ? no_collision : *std::min_element(ttc.begin(), ttc.end());

  // The map column: every obstacle forecast with τ_i (spec §6).
  std::vector<clearance_set> clearance_by_forecast;
  for (std::size_t i = 0; i < tau_count; ++i) {
    std::vector<const clearance_set*> parts;
    for (std::size_t j = 0; j < n; ++j) parts.push_back(&clearance[j][i]);
    clearance_by_forecast.push_back(evaluate.combined(parts));
    const maneuverability_pair mi = evaluate.indices(clearance_by_forecast.back());
    result.mi_brake.push_back(mi.brake);
    result.mi_accelerate.push_back(mi.accelerate);
  }
  result.excluded = excluded_forecast_times(taus, result.time_to_collision);

  // Forecast times (spec §7, §9): obstacle j may use τ_i ≤ TTC_j (and always τ_0 = 0).
  assignment_problem problem;
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<std::size_t> allowed;
    for (std::size_t i = 0; i < tau_count; ++i) {
      if (i == 0 || taus[i] <= ttc[j]) allowed.push_back(i);
    }
    problem.candidates.push_back(std::move(allowed));
  }
  problem.room = [&](std::span<const std::size_t> index) {
    std::vector<const clearance_set*> parts;
    for (std::size_t j = 0; j < index.size(); ++j) parts.push_back(&clearance[j][index[j]]);
    return evaluate.room(evaluate.combined(parts));
  };
  problem.room_alone = [&](std::size_t j, std::size_t i) { return evaluate.room(clearance[j][i]); };

  std::vector<std::size_t> assignment(n, 0);
  if (config.policy.kind == forecast_policy_kind::constant) {
    const auto wanted = static_cast<std::size_t>(std::lround(config.policy.constant_forecast_time / config.forecast_step));
    for (std::size_t j = 0; j < n; ++j) {
      const auto& c = problem.candidates[j];
      assignment[j] = *std::prev(std::upper_bound(c.begin(), c.end(), wanted));
    }
  } else if (n == 1) {
    assignment[0] = adjustable_forecast_index(result.mi_brake, result.mi_accelerate, result.excluded);
  } else if (n > 1) {
    if (options.assignment_search == assignment_search_kind::exhaustive) {
      const std::size_t count = assignment_count(problem);
      if (count > config.max_exhaustive_assignments) {
        return invalid("config.max_exhaustive_assignments = " + std::to_string(config.max_exhaustive_assignments) +
                       ": the exhaustive forecast-time search over " + std::to_string(n) + " obstacles needs " +
                       std::to_string(count) + " assignments; raise the limit or use the coordinate-ascent search");
      }
      assignment = exhaustive_assignment_search(problem).forecast_index;
    } else {
      assignment = coordinate_ascent_assignment_search(problem).forecast_index;
    }
  }
  std::vector<const clearance_set*> assigned_parts;
  for (std::size_t j = 0; j < n; ++j) assigned_parts.push_back(&clearance[j][assignment[j]]);
  const clearance_set assigned = evaluate.combined(assigned_parts);
  const sample_mask colliding = evaluate.colliding(assigned);
  const maneuverability_pair selected = evaluate.indices(assigned);
  result.mi_brake_selected = selected.brake;
  result.mi_accelerate_selected = selected.accelerate;
  result.selected_family = select_family(selected.brake, selected.accelerate);
  if (n > 0) {
    const auto most_urgent = static_cast<std::size_t>(std::min_element(ttc.begin(), ttc.end()) - ttc.begin());
    result.forecast_index = assignment[most_urgent];
  } else if (config.policy.kind == forecast_policy_kind::constant) {
    result.forecast_index = constant_forecast_index(taus, config.policy.constant_forecast_time, result.excluded);
  }
  result.forecast_time = taus[result.forecast_index];
  for (std::size_t j = 0; j < n; ++j) result.obstacles[relevant_track[j]].forecast_index = assignment[j];

  // The maneuver (spec §8).
  std::vector<double> assigned_tau(n);
  for (std::size_t j = 0; j < n; ++j) assigned_tau[j] = taus[assignment[j]];
  choice_input choice;
  choice.samples = &samples;
  choice.colliding = &colliding;
  choice.selected_family = result.selected_family;
  choice.nominal = nominal;
  // Safe means collision-free in continuous time, not only at the sample times: a minimal-effort
  // choice lies at the edge of the safe set, where a corner can clip between samples.
  choice.verify = [&](const maneuver& u) {
    return verified_collision_free(ego, u, relevant, assigned_tau, window, verification_resolution);
  };
  choice.nominal_safe = choice.verify(nominal);
  choice.initial_speed = ego.speed;
  choice.weights = config.effort;
  choice.urgent_steering = config.urgent_steering;
  if (const auto decision = choose_maneuver(choice)) {
    result.command = decision->command;
    result.mode = decision->mode;
  } else {
    std::vector<double> first_collision(samples.size());
    for (std::size_t m = 0; m < samples.size(); ++m) {
      first_collision[m] = first_collision_time(ego, samples.maneuvers[m], relevant, assigned_tau, window);
    }
    const maneuver_decision last_resort = near_crash_maneuver(samples, first_collision, nominal.curvature);
    result.command = last_resort.command;
    result.mode = last_resort.mode;
  }

  if (config.record_samples) {
    sample_snapshot snapshot;
    snapshot.maneuvers = samples.maneuvers;
    snapshot.families = samples.families;
    snapshot.area_weights = samples.area_weights;
    const std::size_t first_column = samples.nominal_column(family::brake).begin;
    for (std::size_t m = 0; m < samples.size(); ++m) {
      snapshot.end_points.push_back(to_world(ego.pose, samples.end_points[m]));
      snapshot.on_nominal_curvature.push_back(m >= first_column ? 1 : 0);
      snapshot.safe_selected.push_back(colliding.test(m) ? 0 : 1);
    }
    for (const clearance_set& c : clearance_by_forecast) {
      std::vector<std::uint8_t> safe(samples.size());
      for (std::size_t m = 0; m < samples.size(); ++m) safe[m] = c[m] > 0.0 ? 1 : 0;
      snapshot.safe_by_forecast.push_back(std::move(safe));
    }
    result.samples = std::move(snapshot);
  }
  return result;
}

}  // namespace mm::detail
