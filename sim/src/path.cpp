#include "mm/sim/path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "mm/maneuver.hpp"
#include "mm/number_text.hpp"

namespace mm::sim {
namespace {

std::string text(vec2 point) { return "[" + number_text(point.x) + ", " + number_text(point.y) + "]"; }

void require_positive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("path: ") + what + " = " + number_text(value) +
                                ": expected a positive finite number");
  }
}

mm::pose segment_pose(const path_segment& seg, double sigma) {
  return {to_world(seg.start, arc_point(seg.curvature, sigma)), seg.start.heading + seg.curvature * sigma};
}

/// σ ∈ [lo, hi] of the point of `seg` nearest to `p`.
double nearest_on_segment(const path_segment& seg, vec2 p, double lo, double hi) {
  const vec2 tangent = unit_vector(seg.start.heading);
  if (seg.curvature == 0.0) return std::clamp(dot(p - seg.start.position, tangent), lo, hi);
  // The centre of the arc; the polar angle about it advances by κσ along the arc.
  const double radius = 1.0 / std::abs(seg.curvature);
  const vec2 left = unit_vector(seg.start.heading + std::numbers::pi / 2.0);
  const vec2 center = seg.start.position + (1.0 / seg.curvature) * left;
  const vec2 to_start = seg.start.position - center;
  const vec2 to_point = p - center;
  double best_sigma = lo;
  double best = squared_norm(segment_pose(seg, lo).position - p);
  const auto consider = [&](double sigma) {
    const double d = squared_norm(segment_pose(seg, sigma).position - p);
    if (d < best) {
      best = d;
      best_sigma = sigma;
    }
  };
  consider(hi);
  if (squared_norm(to_point) > 0.0) {
    const double polar = std::atan2(cross(to_start, to_point), dot(to_start, to_point));
    const double turn = seg.curvature > 0.0 ? polar : -polar;
    const double period = 2.0 * std::numbers::pi * radius;
    double sigma = (turn < 0.0 ? turn + 2.0 * std::numbers::pi : turn) * radius;
    if (sigma < lo) sigma += period * std::ceil((lo - sigma) / period);
    if (sigma <= hi) consider(sigma);
  }
  return best_sigma;
}

}  // namespace

path::path(const mm::pose& start) : end_{start.position, wrap_angle(start.heading)} {}

path path::polyline(std::span<const vec2> points) {
  if (points.size() < 2) throw std::invalid_argument("path: a polyline needs at least 2 points");
  path result(mm::pose{points[0], 0.0});
  for (std::size_t i = 1; i < points.size(); ++i) result.line_to(points[i]);
  return result;
}

path path::circular_arc(vec2 center, double radius, double start_angle, double sweep) {
  require_positive(radius, "radius");
  if (!std::isfinite(start_angle) || !std::isfinite(sweep) || sweep == 0.0) {
    throw std::invalid_argument("path: a circular arc needs a finite start angle and a finite non-zero sweep");
  }
  const double direction = sweep > 0.0 ? 1.0 : -1.0;
  path result(mm::pose{center + radius * unit_vector(start_angle), start_angle + direction * std::numbers::pi / 2.0});
  result.turn(radius, sweep);
  return result;
}

path& path::straight(double length) {
  require_positive(length, "straight length");
  const path_segment seg{end_, length, 0.0, this->length()};
  segments_.push_back(seg);
  end_ = segment_pose(seg, length);
  return *this;
}

path& path::turn(double radius, double angle) {
  require_positive(radius, "turn radius");
  if (!std::isfinite(angle) || angle == 0.0) {
    throw std::invalid_argument("path: turn angle = " + number_text(angle) + ": expected a finite non-zero angle");
  }
  const double curvature = (angle > 0.0 ? 1.0 : -1.0) / radius;
  const path_segment seg{end_, radius * std::abs(angle), curvature, length()};
  segments_.push_back(seg);
  const mm::pose end = segment_pose(seg, seg.length);
  end_ = {end.position, wrap_angle(end.heading)};
  return *this;
}

path& path::line_to(vec2 point) {
  const vec2 d = point - end_.position;
  const double n = norm(d);
  if (!(std::isfinite(n) && n > 0.0)) {
    throw std::invalid_argument("path: line_to " + text(point) + ": expected a finite point other than the current end " +
                                text(end_.position));
  }
  const double heading = std::atan2(d.y, d.x);
  segments_.push_back({{end_.position, heading}, n, 0.0, length()});
  end_ = {point, heading};
  return *this;
}

path& path::curve(double length, double curvature) {
  require_positive(length, "curve length");
  if (!std::isfinite(curvature)) {
    throw std::invalid_argument("path: curve curvature = " + number_text(curvature) + ": expected a finite number [1/m]");
  }
  const path_segment seg{end_, length, curvature, this->length()};
  segments_.push_back(seg);
  const mm::pose end = segment_pose(seg, length);
  end_ = {end.position, wrap_angle(end.heading)};
  return *this;
}

double path::length() const {
  if (segments_.empty()) return 0.0;
  return segments_.back().start_arc_length + segments_.back().length;
}

std::size_t path::segment_index(double arc_length) const {
  const auto after = std::upper_bound(segments_.begin(), segments_.end(), arc_length,
                                      [](double s, const path_segment& seg) { return s < seg.start_arc_length; });
  return after == segments_.begin() ? 0 : static_cast<std::size_t>(after - segments_.begin()) - 1;
}

path_point path::at(double arc_length) const {
  const path_segment& first = segments_.front();
  if (arc_length < 0.0) {
    return {first.start.position + arc_length * unit_vector(first.start.heading), wrap_angle(first.start.heading), 0.0};
  }
  const double total = length();
  if (arc_length > total) {
    return {end_.position + (arc_length - total) * unit_vector(end_.heading), end_.heading, 0.0};
  }
  const path_segment& seg = segments_[segment_index(arc_length)];
  const double sigma = std::clamp(arc_length - seg.start_arc_length, 0.0, seg.length);
  const mm::pose p = segment_pose(seg, sigma);
  return {p.position, wrap_angle(p.heading), seg.curvature};
}

path_projection path::project(vec2 point) const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return project_within(point, -inf, inf);
}

path_projection path::project(vec2 point, double hint, double window) const {
  return project_within(point, hint - window, hint + window);
}

path_projection path::project_within(vec2 point, double lo, double hi) const {
  const double total = length();
  double best_s = 0.0;
  double best = std::numeric_limits<double>::infinity();
  const auto consider = [&](double s, vec2 position) {
    const double d = squared_norm(position - point);
    if (d < best) {
      best = d;
      best_s = s;
    }
  };
  const path_segment& first = segments_.front();
  if (lo < 0.0) {
    const vec2 tangent = unit_vector(first.start.heading);
    const double s = std::clamp(dot(point - first.start.position, tangent), lo, std::min(hi, 0.0));
    consider(s, first.start.position + s * tangent);
  }
  const double inner_lo = std::max(lo, 0.0);
  const double inner_hi = std::min(hi, total);
  if (inner_lo <= inner_hi) {
    for (std::size_t i = segment_index(inner_lo); i < segments_.size(); ++i) {
      const path_segment& seg = segments_[i];
      if (seg.start_arc_length > inner_hi) break;
      const double a = std::max(inner_lo - seg.start_arc_length, 0.0);
      const double b = std::min(inner_hi - seg.start_arc_length, seg.length);
      if (a > b) continue;
      const double sigma = nearest_on_segment(seg, point, a, b);
      consider(seg.start_arc_length + sigma, segment_pose(seg, sigma).position);
    }
  }
  if (hi > total) {
    const vec2 tangent = unit_vector(end_.heading);
    const double s = std::clamp(total + dot(point - end_.position, tangent), std::max(lo, total), hi);
    consider(s, end_.position + (s - total) * tangent);
  }
  path_projection result;
  result.arc_length = best_s;
  result.nearest = at(best_s);
  result.distance = std::sqrt(best);
  const double side = cross(unit_vector(result.nearest.heading), point - result.nearest.position);
  result.lateral_offset = side < 0.0 ? -result.distance : result.distance;
  return result;
}

path_steps steps_of(const path& p) {
  const std::span<const path_segment> segments = p.segments();
  path_steps out{segments.empty() ? p.end_pose() : segments.front().start, {}};
  path rebuilt(out.start);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const path_segment& seg = segments[i];
    const mm::pose end = i + 1 < segments.size() ? segments[i + 1].start : p.end_pose();
    path_step step;
    if (seg.curvature != 0.0) {
      step = {path_step::kind::curve, seg.length, seg.curvature, {}};
      rebuilt.curve(seg.length, seg.curvature);
    } else if (const path alone = path(rebuilt.end_pose()).straight(seg.length);  // what straight adds
               alone.segments().front().start == seg.start && seg.start_arc_length == rebuilt.length() &&
               alone.end_pose().position == end.position) {
      step = {path_step::kind::straight, seg.length, 0.0, {}};
      rebuilt.straight(seg.length);
    } else {
      step = {path_step::kind::line_to, 0.0, 0.0, end.position};
      rebuilt.line_to(end.position);
    }
    out.steps.push_back(step);
  }
  if (!(rebuilt == p)) throw std::logic_error("path: its segments are not rebuilt bit for bit by curve, straight and line_to");
  return out;
}

path path_of(const path_steps& steps) {
  path p(steps.start);
  for (const path_step& step : steps.steps) {
    switch (step.operation) {
      case path_step::kind::curve: p.curve(step.length, step.curvature); break;
      case path_step::kind::straight: p.straight(step.length); break;
      case path_step::kind::line_to: p.line_to(step.point); break;
    }
  }
  return p;
}

}  // namespace mm::sim
