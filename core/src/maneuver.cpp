#include "mm/maneuver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mm {

double max_curvature(double speed, const ego_limits& limits) {
  if (!limits.steering) return 0.0;
  const double geometric = 1.0 / limits.min_turning_radius;
  const double v2 = speed * speed;
  if (v2 * geometric <= limits.max_lateral_acceleration) return geometric;
  return limits.max_lateral_acceleration / v2;
}

double speed_after(double initial_speed, double acceleration, double t, double speed_cap) {
  return std::clamp(initial_speed + acceleration * t, 0.0, speed_cap);
}

double travelled_distance(double initial_speed, double acceleration, double t, double speed_cap) {
  // One piece when the speed at t is inside (0, v_cap) by more than 10⁻⁹ of the speeds involved: the
  // reference's quotients −v0/a and (v_cap − v0)/a are then beyond t (or ≤ 0) after rounding, its
  // breaks collapse onto 0 and t, and its one trapezoid is this one, operation for operation.
  if (t > 0.0 && acceleration != 0.0 && initial_speed >= 0.0 && initial_speed <= speed_cap) {
    const double end = initial_speed + acceleration * t;
    const double slack = 1e-9 * (speed_cap + std::abs(acceleration) * t);
    if (end > slack && end < speed_cap - slack) {
      return 0.5 * (speed_after(initial_speed, acceleration, 0.0, speed_cap) +
                    speed_after(initial_speed, acceleration, t, speed_cap)) *
             t;
    }
  }
  return travelled_distance_reference(initial_speed, acceleration, t, speed_cap);
}

double travelled_distance_reference(double initial_speed, double acceleration, double t, double speed_cap) {
  if (t <= 0.0) return 0.0;
  if (acceleration == 0.0) return std::clamp(initial_speed, 0.0, speed_cap) * t;
  // v0 + a·τ crosses 0 and v_cap at these times; between consecutive break points the clamped
  // speed is linear, so the trapezoid rule is exact on each piece.
  const double stop = std::clamp(-initial_speed / acceleration, 0.0, t);
  const double cap = std::clamp((speed_cap - initial_speed) / acceleration, 0.0, t);
  const std::array<double, 4> breaks{0.0, std::min(stop, cap), std::max(stop, cap), t};
  double distance = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double t0 = breaks[i];
    const double t1 = breaks[i + 1];
    if (t1 <= t0) continue;
    distance += 0.5 * (speed_after(initial_speed, acceleration, t0, speed_cap) +
                       speed_after(initial_speed, acceleration, t1, speed_cap)) *
                (t1 - t0);
  }
  return distance;
}

vec2 arc_point(double curvature, double arc_length) {
  const double turn = curvature * arc_length;
  return {arc_length * sinc(turn), arc_length * versine_ratio(turn)};
}

namespace {

/// Where the maneuver's arc and straight part put the ego at time t, in the frame of the start,
/// and the turn κs [rad] of the arc.
struct local_motion {
  placement at;
  double turn;
};

/// `arc_placement`, and the turn κs [rad].
local_motion arc_motion(double s, double curvature) {
  const double turn = curvature * s;
  if (std::abs(turn) < 1e-4) {
    // Series of arc_point and of the direction: the next terms are below the rounding.
    const double turn2 = turn * turn;
    return {{{s * (1.0 - turn2 / 6.0), s * (turn / 2.0 - turn * turn2 / 24.0)},
             {1.0 - turn2 / 2.0, turn - turn * turn2 / 6.0}},
            turn};
  }
  const double half_sine = std::sin(turn / 2.0);
  const double half_cosine = std::cos(turn / 2.0);
  const double sine = 2.0 * half_sine * half_cosine;
  const double versine = 2.0 * half_sine * half_sine;  // 1 − cos, without cancellation
  return {{{s * (sine / turn), s * (versine / turn)}, {1.0 - versine, sine}}, turn};
}

local_motion move(double initial_speed, const maneuver& u, double t, double horizon, double speed_cap) {
  const local_motion arc =
      arc_motion(travelled_distance(initial_speed, u.acceleration, std::min(t, horizon), speed_cap), u.curvature);
  vec2 local = arc.at.position;
  const vec2 along = arc.at.direction;
  const double turn = arc.turn;
  if (t > horizon) {
    const double straight = speed_after(initial_speed, u.acceleration, horizon, speed_cap) * (t - horizon);
    local = local + straight * along;
  }
  return {{local, along}, turn};
}

}  // namespace

placement arc_placement(double arc_length, double curvature) { return arc_motion(arc_length, curvature).at; }

placement maneuver_local_placement(double initial_speed, const maneuver& u, double t, double horizon,
                                   double speed_cap) {
  return move(initial_speed, u, t, horizon, speed_cap).at;
}

placement maneuver_placement(const pose& start, vec2 start_direction, double initial_speed, const maneuver& u,
                             double t, double horizon, double speed_cap) {
  const placement local = maneuver_local_placement(initial_speed, u, t, horizon, speed_cap);
  return {start.position + rotated(local.position, start_direction.x, start_direction.y),
          rotated(local.direction, start_direction.x, start_direction.y)};
}

pose maneuver_local_pose(double initial_speed, const maneuver& u, double t, double horizon, double speed_cap) {
  const local_motion m = move(initial_speed, u, t, horizon, speed_cap);
  return {m.at.position, m.turn};
}

pose maneuver_pose(const pose& start, double initial_speed, const maneuver& u, double t,
                   double horizon, double speed_cap) {
  const pose local = maneuver_local_pose(initial_speed, u, t, horizon, speed_cap);
  return {to_world(start, local.position), start.heading + local.heading};
}

maneuver clamp_to_limits(const maneuver& u, double initial_speed, const ego_limits& limits) {
  const double kappa_max = max_curvature(initial_speed, limits);
  return {std::clamp(u.acceleration, -limits.max_deceleration, limits.max_acceleration),
          std::clamp(u.curvature, -kappa_max, kappa_max)};
}

}  // namespace mm
