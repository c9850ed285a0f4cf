#include "pipeline.hpp"

#include <algorithm>
#include <cmath>
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

  // Obstacles: estimate, keep those that can interact (the others cost nothing).
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

  collision_window window{config.displacement_horizon, config.collision_window, options.max_time_step,
                          config.safety_margin};
  for (const forecast_obstacle& o : relevant) {
    window.time_step = std::min(window.time_step, tunneling_time_step(ego, o, window));
  }
  window.time_step = std::min(window.time_step, config.collision_window);
  result.collision_time_step = window.time_step;

  const maneuver_samples samples = sample_maneuvers(ego, nominal.curvature, config.displacement_horizon, options.resolution);
  const std::size_t n = relevant.size();

  // Collision sets [CSS](τ_i) and TTC per relevant obstacle (spec §5, §6).
  assignment_problem problem;
  problem.samples = &samples;
  std::vector<double> ttc(n, no_collision);
  {
    std::optional<ego_sweep> sweep;
    if (!options.brute_force_collision_sets && n > 0) sweep.emplace(ego, samples, window);
    for (std::size_t j = 0; j < n; ++j) {
      problem.collision_sets.push_back(options.brute_force_collision_sets
                                           ? collision_sets_reference(ego, samples, relevant[j], taus, window)
                                           : collision_sets(*sweep, relevant[j], taus));
      ttc[j] = time_to_collision(ego, nominal, relevant[j], window);
      result.obstacles[relevant_track[j]].time_to_collision = ttc[j];
      std::vector<std::size_t> allowed;
      for (std::size_t i = 0; i < tau_count; ++i) {
        if (i == 0 || taus[i] <= ttc[j]) allowed.push_back(i);
      }
      problem.candidates.push_back(std::move(allowed));
    }
  }
  result.time_to_collision = n == 0 ? no_collision : *std::min_element(ttc.begin(), ttc.end());

  // The map column: every obstacle forecast with τ_i (spec §6).
  std::vector<sample_mask> colliding_by_forecast(tau_count, sample_mask(samples.size()));
  for (std::size_t i = 0; i < tau_count; ++i) {
    for (std::size_t j = 0; j < n; ++j) colliding_by_forecast[i] |= problem.collision_sets[j][i];
    const maneuverability_pair mi = maneuverability_indices(samples, colliding_by_forecast[i]);
    result.mi_brake.push_back(mi.brake);
    result.mi_accelerate.push_back(mi.accelerate);
  }
  result.excluded = excluded_forecast_times(taus, result.time_to_collision);

  // Forecast times (spec §7, §9).
  std::vector<std::size_t> assignment(n, 0);
  if (config.policy.kind == forecast_policy_kind::constant) {
    const std::size_t wanted = static_cast<std::size_t>(std::lround(config.policy.constant_forecast_time / config.forecast_step));
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
                       ": the exhaustive forecast-time search over " + std::to_string(n) +
                       " obstacles needs " + std::to_string(count) +
                       " assignments; raise the limit or use the coordinate-ascent search");
      }
      assignment = exhaustive_assignment_search(problem).forecast_index;
    } else {
      assignment = coordinate_ascent_assignment_search(problem).forecast_index;
    }
  }
  const sample_mask colliding = colliding_under(problem, assignment);
  const maneuverability_pair selected = maneuverability_indices(samples, colliding);
  result.mi_brake_selected = selected.brake;
  result.mi_accelerate_selected = selected.accelerate;
  result.selected_family = select_family(selected.brake, selected.accelerate);
  if (n > 0) {
    const std::size_t most_urgent = static_cast<std::size_t>(std::min_element(ttc.begin(), ttc.end()) - ttc.begin());
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
  choice.nominal_safe = !maneuver_collides(ego, nominal, relevant, assigned_tau, window);
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
    const maneuver_decision last_resort = near_crash_maneuver(samples, first_collision);
    result.command = last_resort.command;
    result.mode = last_resort.mode;
  }

  if (config.record_samples) {
    sample_snapshot snapshot;
    snapshot.maneuvers = samples.maneuvers;
    snapshot.families = samples.families;
    snapshot.area_weights = samples.area_weights;
    for (std::size_t m = 0; m < samples.size(); ++m) {
      snapshot.end_points.push_back(to_world(ego.pose, samples.end_points[m]));
      snapshot.on_nominal_curvature.push_back(m >= samples.nominal_column(family::brake).begin ? 1 : 0);
      snapshot.safe_selected.push_back(colliding.test(m) ? 0 : 1);
    }
    for (const sample_mask& mask : colliding_by_forecast) {
      std::vector<std::uint8_t> safe(samples.size());
      for (std::size_t m = 0; m < samples.size(); ++m) safe[m] = mask.test(m) ? 0 : 1;
      snapshot.safe_by_forecast.push_back(std::move(safe));
    }
    result.samples = std::move(snapshot);
  }
  return result;
}

}  // namespace mm::detail
