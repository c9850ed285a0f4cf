#include "mm/sim/follower.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mm::sim {

double lookahead_distance(double speed, const follower_config& config) {
  return std::max(config.min_lookahead, config.lookahead_time * speed);
}

double pure_pursuit_curvature(const mm::pose& vehicle, vec2 goal) {
  const vec2 local = to_local(vehicle, goal);
  const double d2 = squared_norm(local);
  return d2 > 0.0 ? 2.0 * local.y / d2 : 0.0;
}

curve_speed_limit curve_speed_limit_ahead(const path& reference, double arc_length, double preview,
                                          double lateral_acceleration, double deceleration) {
  curve_speed_limit limit;
  const double end = arc_length + preview;
  for (const path_segment& seg : reference.segments()) {
    if (seg.start_arc_length > end) break;
    if (seg.start_arc_length + seg.length < arc_length || seg.curvature == 0.0) continue;
    const double curve_speed = std::sqrt(lateral_acceleration / std::abs(seg.curvature));
    const double distance = std::max(0.0, seg.start_arc_length - arc_length);
    const double speed = std::sqrt(curve_speed * curve_speed + 2.0 * deceleration * distance);
    if (speed < limit.speed) limit = {speed, curve_speed, distance};
  }
  return limit;
}

double car_following_acceleration(double speed, const leader& ahead, const car_following_config& config,
                                  double max_acceleration, double comfortable_deceleration) {
  if (!(ahead.gap > 0.0)) return -std::numeric_limits<double>::infinity();
  const double closing = speed - ahead.speed;
  const double desired_gap =
      config.jam_distance +
      std::max(0.0, speed * config.time_gap +
                        speed * closing / (2.0 * std::sqrt(max_acceleration * comfortable_deceleration)));
  const double ratio = desired_gap / ahead.gap;
  return max_acceleration * (1.0 - ratio * ratio);
}

double lagging_acceleration(double arc_length, double speed, const scripted_sample& script, double cap,
                            const scripted_car_following& config) {
  const double k = config.speed_gain;
  const double closing =
      script.acceleration + k * (script.speed - speed) + k * k * (script.arc_length - arc_length);
  return std::clamp(std::min(closing, cap), -config.max_deceleration, config.max_acceleration);
}

follower_command follow_path(const path& reference, double arc_length, const mm::pose& vehicle, double speed,
                             double desired_speed, const follower_config& config, const ego_limits& limits) {
  follower_command command;
  command.lookahead = lookahead_distance(speed, config);
  command.goal = reference.at(arc_length + command.lookahead).position;
  const double curvature = pure_pursuit_curvature(vehicle, command.goal);

  const double b = config.comfortable_deceleration;
  const double lateral = config.curve_lateral_acceleration.value_or(limits.max_lateral_acceleration);
  const double fastest = std::max(speed, desired_speed);
  const curve_speed_limit curve =
      curve_speed_limit_ahead(reference, arc_length, fastest * fastest / (2.0 * b) + command.lookahead, lateral, b);
  command.target_speed = std::min(desired_speed, curve.speed);
  const bool braking_for_curve = curve.speed < desired_speed && curve.distance > 0.0 && speed > curve.curve_speed;
  const double acceleration = config.speed_gain * (command.target_speed - speed) - (braking_for_curve ? b : 0.0);
  command.nominal = clamp_to_limits({acceleration, curvature}, speed, limits);
  return command;
}

}  // namespace mm::sim
