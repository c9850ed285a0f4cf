#include <cmath>
#include <span>
#include <string>
#include <type_traits>

#include "mm/collision.hpp"
#include "mm/number_text.hpp"
#include "mm/planner.hpp"

namespace mm {
namespace {

/// A field name or an expectation: text, or a callable that builds it (only when a check fails).
template <class Text>
std::string text(Text&& t) {
  if constexpr (std::is_invocable_v<Text>) {
    return std::string(t());
  } else {
    return std::string(t);
  }
}

/// The first problem among the checks, each a (condition that must hold, field, value,
/// expectation). Names and expectations are built only for the failing check: planning validates
/// every input, and most inputs are valid.
struct checker {
  std::optional<std::string> error;
  template <class Field, class What>
  void require(bool ok, Field&& field, double value, What&& what) {
    if (!error && !ok) error = text(field) + " = " + number_text(value) + ": expected " + text(what);
  }
  template <class Field>
  void finite(Field&& field, double value) {
    require(std::isfinite(value), field, value, "a finite number");
  }
  template <class Field>
  void positive(Field&& field, double value, const char* unit) {
    require(std::isfinite(value) && value > 0.0, field, value, [&] { return std::string("a positive finite number of ") + unit; });
  }
  template <class Field>
  void non_negative(Field&& field, double value, const char* unit) {
    require(std::isfinite(value) && value >= 0.0, field, value, [&] { return std::string("a finite number ≥ 0 of ") + unit; });
  }
  /// A positive finite number up to `largest`; `note` follows the expectation.
  template <class Field>
  void positive_up_to(Field&& field, double value, double largest, const char* unit, const char* note = "") {
    require(std::isfinite(value) && value > 0.0 && value <= largest, field, value, [&] {
      return "a positive number of " + std::string(unit) + " up to " + number_text(largest) + note;
    });
  }
  template <class Field>
  void coordinate(Field&& field, double value) {
    require(std::isfinite(value) && std::abs(value) <= largest_input_coordinate, field, value,
            [&] { return "a finite coordinate within ±" + number_text(largest_input_coordinate) + " m"; });
  }
  template <class Field>
  void pose(Field&& field, const mm::pose& p) {
    coordinate([&] { return text(field) + ".position.x"; }, p.position.x);
    coordinate([&] { return text(field) + ".position.y"; }, p.position.y);
    finite([&] { return text(field) + ".heading"; }, p.heading);
  }
  template <class Field>
  void speed(Field&& field, double value) {
    require(std::isfinite(value) && std::abs(value) <= largest_input_speed, field, value,
            [&] { return "a finite speed within ±" + number_text(largest_input_speed) + " m/s"; });
  }
  template <class Field>
  void shape(Field&& field, const footprint& f) {
    if (error) return;
    if (auto why = footprint_error(f)) error = text(field) + ": " + *why;
  }
};

/// True when every observation of `history` is finite, within the input bounds and later than the
/// one before: what the observation checks of `validation_error` accept, in one pass that builds no
/// message.
bool history_valid(std::span<const observation> history) {
  for (std::size_t i = 0; i < history.size(); ++i) {
    const observation& o = history[i];
    const bool in_range = std::isfinite(o.time) && std::abs(o.pose.position.x) <= largest_input_coordinate &&
                          std::abs(o.pose.position.y) <= largest_input_coordinate && std::isfinite(o.pose.heading) &&
                          std::abs(o.speed) <= largest_input_speed;
    if (!in_range || (i > 0 && !(o.time > history[i - 1].time))) return false;
  }
  return true;
}

}  // namespace

std::optional<std::string> validation_error(const plan_input& in) {
  checker c;
  c.finite("time", in.time);

  const ego_limits& l = in.ego.limits;
  c.positive_up_to("ego.limits.max_acceleration", l.max_acceleration, largest_input_acceleration, "m/s²");
  c.positive_up_to("ego.limits.max_deceleration", l.max_deceleration, largest_input_acceleration, "m/s²",
                   " (deceleration is given as a positive number)");
  c.positive_up_to("ego.limits.max_lateral_acceleration", l.max_lateral_acceleration, largest_input_acceleration, "m/s²");
  c.require(std::isfinite(l.min_turning_radius) && l.min_turning_radius >= smallest_input_turning_radius,
            "ego.limits.min_turning_radius", l.min_turning_radius,
            [&] { return "a finite number of metres of at least " + number_text(smallest_input_turning_radius); });
  c.positive_up_to("ego.limits.speed_cap", l.speed_cap, largest_input_speed, "m/s");
  c.pose("ego.pose", in.ego.pose);
  c.non_negative("ego.speed", in.ego.speed, "m/s");
  c.require(!(in.ego.speed > l.speed_cap), "ego.speed", in.ego.speed,
            [&] { return "at most ego.limits.speed_cap = " + number_text(l.speed_cap) + " m/s"; });
  c.shape("ego.shape", in.ego.shape);
  c.finite("nominal.acceleration", in.nominal.acceleration);
  c.finite("nominal.curvature", in.nominal.curvature);

  const planner_config& k = in.config;
  c.positive("config.displacement_horizon", k.displacement_horizon, "seconds");
  c.positive("config.collision_window", k.collision_window, "seconds");
  c.require(!(k.collision_window < k.displacement_horizon), "config.collision_window", k.collision_window,
            [&] { return "at least config.displacement_horizon = " + number_text(k.displacement_horizon) + " s"; });
  c.positive("config.forecast_step", k.forecast_step, "seconds");
  c.require(k.forecast_count >= 1, "config.forecast_count", static_cast<double>(k.forecast_count),
            "at least 1 (the forecast grid is empty)");
  c.require(k.forecast_count <= largest_forecast_count, "config.forecast_count", static_cast<double>(k.forecast_count),
            "at most 1000");
  const double largest_forecast = static_cast<double>(k.forecast_count == 0 ? 0 : k.forecast_count - 1) * k.forecast_step;
  c.require(!(largest_forecast > k.collision_window + 1e-9), "config.forecast_count", static_cast<double>(k.forecast_count),
            [&] {
              return "a forecast grid within the collision window: the largest forecast time " +
                     number_text(largest_forecast) + " s exceeds config.collision_window = " +
                     number_text(k.collision_window) + " s";
            });
  c.positive("config.history_window", k.history_window, "seconds");
  c.require(std::isfinite(k.safety_margin) && k.safety_margin >= 0.0 && k.safety_margin <= largest_input_safety_margin,
            "config.safety_margin", k.safety_margin,
            [&] { return "a number of metres from 0 to " + number_text(largest_input_safety_margin); });
  c.non_negative("config.effort.longitudinal", k.effort.longitudinal, "s⁴/m²");
  c.non_negative("config.effort.lateral", k.effort.lateral, "s⁴/m²");
  c.require(k.resolution.accelerations >= 2 && k.resolution.accelerations <= largest_sampling_side,
            "config.resolution.accelerations",
            static_cast<double>(k.resolution.accelerations), "an integer from 2 to 2001");
  c.require(k.resolution.curvatures >= 1 && k.resolution.curvatures <= largest_sampling_side,
            "config.resolution.curvatures",
            static_cast<double>(k.resolution.curvatures), "an integer from 1 to 2001");
  c.positive("config.max_time_step", k.max_time_step, "seconds");
  c.require(!(k.max_time_step < smallest_collision_time_step), "config.max_time_step", k.max_time_step,
            "at least 0.0001 s, the shortest collision time step the planner takes");
  if (!c.error) {
    // The window's sample times for every sampled maneuver: bounded, like the resolution.
    const double maneuvers = sampled_maneuver_count(k.resolution);
    const double times = sample_time_count(k.collision_window, k.max_time_step);
    c.require(!(maneuvers * times > largest_sample_time_pairs), "config.collision_window", k.collision_window, [&] {
      // Four significant digits, rounded down: still within the bound.
      const double longest = (std::floor(largest_sample_time_pairs / maneuvers) - 1.0) * k.max_time_step * (1.0 - 1e-3);
      return "at most " + number_text(longest, 4) + " s with config.max_time_step = " + number_text(k.max_time_step) +
             " s and config.resolution " + std::to_string(k.resolution.accelerations) + " × " +
             std::to_string(k.resolution.curvatures) + ": " + number_text(times) + " sample times for " +
             number_text(maneuvers) + " sampled maneuvers exceed the 5e8 pairs a planning step may hold";
    });
  }
  c.require(k.max_exhaustive_assignments >= 1, "config.max_exhaustive_assignments",
            static_cast<double>(k.max_exhaustive_assignments), "at least 1");
  if (k.policy.kind == forecast_policy_kind::constant) {
    const double tau = k.policy.constant_forecast_time;
    c.non_negative("config.policy.constant_forecast_time", tau, "seconds");
    const double steps = tau / k.forecast_step;
    c.require(!(std::abs(steps - std::round(steps)) > 1e-6 || tau > largest_forecast + 1e-9),
              "config.policy.constant_forecast_time", tau,
              [&] {
                return "a forecast time on the grid: a multiple of config.forecast_step = " +
                       number_text(k.forecast_step) + " s from 0 to " + number_text(largest_forecast) + " s";
              });
  }

  for (std::size_t j = 0; j < in.obstacles.size() && !c.error; ++j) {
    const obstacle_track& o = in.obstacles[j];
    const auto field = [&] { return "obstacles[" + std::to_string(j) + "] (id " + std::to_string(o.id) + ")"; };
    c.shape([&] { return field() + ".shape"; }, o.shape);
    // Speed and yaw rate are estimated from two observations or more, unless the caller gives them.
    const std::size_t needed = o.kind == obstacle_kind::static_obstacle || o.motion ? 1 : 2;
    c.require(o.history.size() >= needed, [&] { return field() + ".history size"; }, static_cast<double>(o.history.size()),
              needed == 1 ? "at least 1 observation"
                          : "at least 2 observations (speed and yaw rate are estimated from the history)");
    // The messages of the observations only for a history that has something wrong.
    const bool history_ok = history_valid(o.history);
    for (std::size_t i = 0; i < o.history.size() && !c.error && !history_ok; ++i) {
      const observation& obs = o.history[i];
      const auto at = [&] { return field() + ".history[" + std::to_string(i) + "]"; };
      c.finite([&] { return at() + ".time"; }, obs.time);
      c.pose([&] { return at() + ".pose"; }, obs.pose);
      c.speed([&] { return at() + ".speed"; }, obs.speed);
      if (i > 0) {
        c.require(obs.time > o.history[i - 1].time, [&] { return at() + ".time"; }, obs.time,
                  [&] { return "a time after the previous observation's " + number_text(o.history[i - 1].time) + " s"; });
      }
    }
    if (!c.error && !o.history.empty()) {
      c.require(!(o.history.back().time > in.time + 1e-9), [&] { return field() + ".history.back().time"; },
                o.history.back().time, [&] { return "no later than the planning time " + number_text(in.time) + " s"; });
      c.require(!(in.time - o.history.back().time > largest_observation_age),
                [&] { return field() + ".history.back().time"; }, o.history.back().time, [&] {
                  return "no more than " + number_text(largest_observation_age) + " s before the planning time " +
                         number_text(in.time) + " s";
                });
    }
    if (!c.error && o.motion) {
      c.pose([&] { return field() + ".motion.pose"; }, o.motion->pose);
      c.non_negative([&] { return field() + ".motion.speed"; }, o.motion->speed, "m/s");
      c.speed([&] { return field() + ".motion.speed"; }, o.motion->speed);
      c.require(std::isfinite(o.motion->yaw_rate) && std::abs(o.motion->yaw_rate) <= largest_input_yaw_rate,
                [&] { return field() + ".motion.yaw_rate"; }, o.motion->yaw_rate,
                [&] { return "a finite yaw rate within ±" + number_text(largest_input_yaw_rate) + " rad/s"; });
    }
  }
  return c.error;
}

}  // namespace mm
