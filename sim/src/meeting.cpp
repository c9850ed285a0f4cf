#include "mm/sim/meeting.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace mm::sim {
namespace {

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

double travel_time(double distance, double speed) {
  if (!(std::isfinite(distance) && distance >= 0.0)) {
    throw std::invalid_argument("the conflict point is " + text(-distance) + " m behind the agent's start");
  }
  if (!(std::isfinite(speed) && speed > 0.0)) {
    throw std::invalid_argument("initial speed " + text(speed) + " m/s: an agent must move to reach the conflict point");
  }
  return distance / speed;
}

double arc_length_at(const path& reference, vec2 point, double tolerance) {
  if (reference.empty()) throw std::invalid_argument("the path is empty");
  const path_projection p = reference.project(point);
  const double length = reference.length();
  const double s = std::clamp(p.arc_length, 0.0, length);
  const double distance = norm(reference.at(s).position - point);
  if (!(distance <= tolerance)) {
    throw std::invalid_argument("the point (" + text(point.x) + ", " + text(point.y) + ") is " + text(distance) +
                                " m from the path; expected at most " + text(tolerance) + " m");
  }
  return s;
}

std::vector<double> meeting_start_times(std::span<const double> start_times, std::span<const meeting> meetings) {
  const std::size_t n = start_times.size();
  for (const meeting& m : meetings) {
    if (m.first >= n || m.second >= n) throw std::invalid_argument("meeting: agent index out of range");
    if (m.first == m.second) throw std::invalid_argument("meeting: an agent cannot meet itself");
    if (!(std::isfinite(m.first_travel_time) && m.first_travel_time >= 0.0) ||
        !(std::isfinite(m.second_travel_time) && m.second_travel_time >= 0.0)) {
      throw std::invalid_argument("meeting: travel times must be finite and ≥ 0");
    }
    if (!std::isfinite(m.lag)) throw std::invalid_argument("meeting: the lag must be finite");
  }
  // Relative start times within each connected group, propagated from its first agent. A
  // meeting fixes start_second − start_first = travel_first + lag − travel_second.
  constexpr double unset = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> relative(n, unset);
  std::vector<std::size_t> group(n, n);
  std::vector<double> result(start_times.begin(), start_times.end());
  for (std::size_t root = 0; root < n; ++root) {
    if (group[root] != n) continue;
    group[root] = root;
    relative[root] = 0.0;
    std::vector<std::size_t> members{root};
    for (std::size_t k = 0; k < members.size(); ++k) {
      const std::size_t at = members[k];
      for (const meeting& m : meetings) {
        if (m.first != at && m.second != at) continue;
        const double offset = m.first_travel_time + m.lag - m.second_travel_time;
        const std::size_t other = m.first == at ? m.second : m.first;
        const double expected = m.first == at ? relative[at] + offset : relative[at] - offset;
        if (group[other] == n) {
          group[other] = root;
          relative[other] = expected;
          members.push_back(other);
        } else if (std::abs(relative[other] - expected) > 1e-9) {
          throw std::invalid_argument("meeting: the meetings contradict each other (a cycle whose arrival times differ by " +
                                      text(relative[other] - expected) + " s)");
        }
      }
    }
    // Shift the group so that nobody starts before its own start time and someone keeps it.
    double shift = -std::numeric_limits<double>::infinity();
    for (std::size_t member : members) shift = std::max(shift, start_times[member] - relative[member]);
    for (std::size_t member : members) result[member] = relative[member] + shift;
  }
  return result;
}

}  // namespace mm::sim
