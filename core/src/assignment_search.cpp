#include "mm/assignment_search.hpp"

#include <algorithm>
#include <limits>

#include "mm/maneuverability.hpp"

namespace mm {

std::string_view to_string(assignment_search_kind kind) {
  return kind == assignment_search_kind::exhaustive ? "exhaustive" : "coordinate_ascent";
}

sample_mask colliding_under(const assignment_problem& problem, std::span<const std::size_t> forecast_index) {
  sample_mask colliding(problem.samples->size());
  for (std::size_t j = 0; j < forecast_index.size(); ++j) {
    colliding |= problem.collision_sets[j][forecast_index[j]];
  }
  return colliding;
}

double assignment_room(const assignment_problem& problem, std::span<const std::size_t> forecast_index) {
  const maneuverability_pair mi = maneuverability_indices(*problem.samples, colliding_under(problem, forecast_index));
  return std::max(mi.brake, mi.accelerate);
}

std::size_t assignment_count(const assignment_problem& problem) {
  std::size_t count = 1;
  for (const auto& c : problem.candidates) {
    if (c.size() != 0 && count > std::numeric_limits<std::size_t>::max() / c.size()) {
      return std::numeric_limits<std::size_t>::max();
    }
    count *= c.size();
  }
  return count;
}

forecast_assignment exhaustive_assignment_search(const assignment_problem& problem) {
  const std::size_t n = problem.candidates.size();
  std::vector<std::size_t> digit(n, 0);  // position in each obstacle's candidate list
  std::vector<std::size_t> index(n);
  forecast_assignment best;
  best.room = -1.0;
  while (true) {
    for (std::size_t j = 0; j < n; ++j) index[j] = problem.candidates[j][digit[j]];
    const double room = assignment_room(problem, index);
    ++best.evaluations;
    if (room > best.room) {
      best.room = room;
      best.forecast_index = index;
    }
    std::size_t j = n;
    while (j > 0) {
      --j;
      if (++digit[j] < problem.candidates[j].size()) break;
      digit[j] = 0;
      if (j == 0) return best;
    }
    if (n == 0) return best;
  }
}

namespace {

/// Coordinate ascent from `start`: obstacle by obstacle, move to the candidate of largest room
/// when it is strictly larger; stop after a sweep without a move.
forecast_assignment ascend(const assignment_problem& problem, std::vector<std::size_t> start, std::size_t& evaluations) {
  forecast_assignment current{std::move(start), 0.0, 0};
  current.room = assignment_room(problem, current.forecast_index);
  ++evaluations;
  constexpr int max_sweeps = 32;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool moved = false;
    for (std::size_t j = 0; j < problem.candidates.size(); ++j) {
      std::vector<std::size_t> trial = current.forecast_index;
      for (const std::size_t candidate : problem.candidates[j]) {
        if (candidate == current.forecast_index[j]) continue;
        trial[j] = candidate;
        const double room = assignment_room(problem, trial);
        ++evaluations;
        if (room > current.room) {
          current.room = room;
          current.forecast_index[j] = candidate;
          moved = true;
        }
      }
    }
    if (!moved) break;
  }
  return current;
}

}  // namespace

forecast_assignment coordinate_ascent_assignment_search(const assignment_problem& problem) {
  const std::size_t n = problem.candidates.size();
  std::size_t evaluations = 0;

  std::vector<std::size_t> individual(n);
  for (std::size_t j = 0; j < n; ++j) {
    double best = -1.0;
    for (const std::size_t candidate : problem.candidates[j]) {
      const maneuverability_pair mi = maneuverability_indices(*problem.samples, problem.collision_sets[j][candidate]);
      ++evaluations;
      if (std::max(mi.brake, mi.accelerate) > best) {
        best = std::max(mi.brake, mi.accelerate);
        individual[j] = candidate;
      }
    }
  }

  std::size_t grid_size = 0;
  for (const auto& c : problem.candidates) grid_size = std::max(grid_size, c.back() + 1);
  std::vector<std::size_t> common(n);
  double common_room = -1.0;
  std::vector<std::size_t> trial(n);
  for (std::size_t i = 0; i < grid_size; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      // The largest allowed index not above i (candidates are ascending and start at 0).
      const auto& c = problem.candidates[j];
      trial[j] = *std::prev(std::upper_bound(c.begin(), c.end(), i));
    }
    const double room = assignment_room(problem, trial);
    ++evaluations;
    if (room > common_room) {
      common_room = room;
      common = trial;
    }
  }

  forecast_assignment a = ascend(problem, std::move(individual), evaluations);
  forecast_assignment b = ascend(problem, std::move(common), evaluations);
  forecast_assignment& best =
      (b.room > a.room || (b.room == a.room && b.forecast_index < a.forecast_index)) ? b : a;
  best.evaluations = evaluations;
  return best;
}

}  // namespace mm
