#include "mm/forecast.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "mm/input_bounds.hpp"

namespace mm {
namespace {

/// Slope and value at `at` of the least-squares line through (t_i, y_i).
struct line_fit {
  double value;
  double slope;
};

/// Fitted relative to the first value, so that constant values give exactly that value and a slope
/// of exactly 0 (a straight, steady obstacle then has ω = 0 and forecasts that do not depend on τ).
line_fit fit_line(const std::vector<double>& t, const std::vector<double>& y, double at) {
  const double n = static_cast<double>(t.size());
  const double origin = y.front();
  double mean_t = 0.0;
  double mean_y = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    mean_t += t[i];
    mean_y += y[i] - origin;
  }
  mean_t /= n;
  mean_y /= n;
  double stt = 0.0;
  double sty = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    stt += (t[i] - mean_t) * (t[i] - mean_t);
    sty += (t[i] - mean_t) * (y[i] - origin - mean_y);
  }
  const double slope = stt > 0.0 ? sty / stt : 0.0;
  return {origin + (mean_y + slope * (at - mean_t)), slope};
}

}  // namespace

std::string_view to_string(obstacle_kind kind) {
  switch (kind) {
    case obstacle_kind::vehicle: return "vehicle";
    case obstacle_kind::pedestrian: return "pedestrian";
    case obstacle_kind::static_obstacle: return "static";
  }
  return "unknown";
}

std::size_t observations_read(const obstacle_track& track, double history_window) {
  if (track.kind == obstacle_kind::static_obstacle) return 1;
  const observation& last = track.history.back();
  std::size_t first = track.history.size() - 2;
  while (first > 0 && track.history[first - 1].time >= last.time - history_window) --first;
  return track.history.size() - first;
}

motion_estimate estimate_motion(const obstacle_track& track, double history_window, double now) {
  const observation& last = track.history.back();
  if (track.kind == obstacle_kind::static_obstacle) return {last.pose, 0.0, 0.0};

  const std::size_t count = observations_read(track, history_window);
  const std::size_t first = track.history.size() - count;
  std::vector<double> times;
  std::vector<double> headings;
  std::vector<double> speeds;
  times.reserve(count);
  headings.reserve(count);
  speeds.reserve(count);
  for (std::size_t i = first; i < track.history.size(); ++i) {
    const observation& o = track.history[i];
    times.push_back(o.time - last.time);
    // Unwrap: each heading is taken within ±π of the previous one.
    headings.push_back(headings.empty() ? o.pose.heading
                                        : headings.back() + wrap_angle(o.pose.heading - headings.back()));
    speeds.push_back(o.speed);
  }
  const line_fit heading = fit_line(times, headings, 0.0);
  const line_fit speed = fit_line(times, speeds, 0.0);
  // Clamped to what the planner takes (input_bounds.hpp): a fit over observations a few
  // microseconds apart can give any slope.
  const motion_estimate at_last{{last.pose.position, wrap_angle(heading.value)},
                                std::clamp(speed.value, 0.0, largest_input_speed),
                                std::clamp(heading.slope, -largest_input_yaw_rate, largest_input_yaw_rate)};
  const double lag = now - last.time;
  if (lag <= 0.0) return at_last;
  return {forecast_pose(at_last, lag, lag), at_last.speed, at_last.yaw_rate};
}

pose forecast_pose(const motion_estimate& motion, double forecast_time, double t) {
  if (motion.yaw_rate == 0.0) {
    // No turn: every forecast time gives the same straight line (computed so, bit for bit).
    return {motion.pose.position + motion.speed * t * unit_vector(motion.pose.heading), motion.pose.heading};
  }
  const double turning_time = std::min(t, forecast_time);
  const double turn = motion.yaw_rate * turning_time;
  // Chord of the CTRV arc: length v·t·sinc(ωt/2), direction θ + ωt/2.
  const double chord = motion.speed * turning_time * sinc(turn / 2.0);
  vec2 position = motion.pose.position + chord * unit_vector(motion.pose.heading + turn / 2.0);
  const double heading = motion.pose.heading + turn;
  if (t > forecast_time) position = position + motion.speed * (t - forecast_time) * unit_vector(heading);
  return {position, heading};
}

}  // namespace mm
