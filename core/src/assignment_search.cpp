#include "mm/assignment_search.hpp"

#include <algorithm>
#include <limits>
#include <unordered_map>
#include <vector>

#include "mm/forecast_policy.hpp"
#include "index_hash.hpp"

namespace mm {

std::string_view to_string(assignment_search_kind kind) {
  return kind == assignment_search_kind::exhaustive ? "exhaustive" : "coordinate_ascent";
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
    const double room = problem.room(index);
    ++best.evaluations;
    if (room > best.room + tie_tolerance) {
      best.room = room;
      best.forecast_index = index;
    }
    std::size_t j = n;
    while (j > 0 && ++digit[j - 1] == problem.candidates[j - 1].size()) digit[--j] = 0;
    if (j == 0) return best;
  }
}

namespace {

using room_function = std::function<double(std::span<const std::size_t>)>;

/// Coordinate ascent from `start`, by `room`.
forecast_assignment ascend(const assignment_problem& problem, const room_function& room_of, std::vector<std::size_t> start,
                           std::size_t& evaluations) {
  forecast_assignment current{std::move(start), 0.0, 0};
  current.room = room_of(current.forecast_index);
  ++evaluations;
  constexpr int max_sweeps = 32;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool moved = false;
    for (std::size_t j = 0; j < problem.candidates.size(); ++j) {
      std::vector<std::size_t> trial = current.forecast_index;
      for (const std::size_t candidate : problem.candidates[j]) {
        if (candidate == current.forecast_index[j]) continue;
        trial[j] = candidate;
        const double room = room_of(trial);
        ++evaluations;
        if (room > current.room + tie_tolerance) {
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
  if (assignment_count(problem) == 1) {
    // One assignment: nothing to search.
    std::vector<std::size_t> only(n);
    for (std::size_t j = 0; j < n; ++j) only[j] = problem.candidates[j].front();
    const double room = problem.room(only);
    return {std::move(only), room, 1};
  }
  std::size_t evaluations = 0;
  const bool rough = static_cast<bool>(problem.rough_room);
  // Every assignment the climb meets, with what it was climbed by.
  std::unordered_map<std::vector<std::size_t>, double, detail::index_hash> met;
  const room_function climb = [&](std::span<const std::size_t> index) {
    const double r = rough ? problem.rough_room(index) : problem.room(index);
    met.emplace(std::vector<std::size_t>(index.begin(), index.end()), r);
    return r;
  };

  std::vector<std::size_t> individual(n);
  for (std::size_t j = 0; j < n; ++j) {
    double best = -1.0;
    for (const std::size_t candidate : problem.candidates[j]) {
      const double room = rough && problem.rough_room_alone ? problem.rough_room_alone(j, candidate)
                                                            : problem.room_alone(j, candidate);
      ++evaluations;
      if (room > best + tie_tolerance) {
        best = room;
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
      const auto& c = problem.candidates[j];
      trial[j] = *std::prev(std::upper_bound(c.begin(), c.end(), i));  // largest allowed index ≤ i
    }
    const double room = climb(trial);
    ++evaluations;
    if (room > common_room + tie_tolerance) {
      common_room = room;
      common = trial;
    }
  }

  forecast_assignment a = ascend(problem, climb, std::move(individual), evaluations);
  forecast_assignment b = ascend(problem, climb, std::move(common), evaluations);
  const auto better = [](const forecast_assignment& x, const forecast_assignment& y) {
    return x.room > y.room + tie_tolerance || (x.room >= y.room - tie_tolerance && x.forecast_index < y.forecast_index);
  };
  forecast_assignment best = better(b, a) ? std::move(b) : std::move(a);
  if (rough) {
    // Ranked by their rooms, in the order of their forecast indices: the assignments whose rough
    // room came close to the best rough room.
    double top = -1.0;
    for (const auto& [index, r] : met) top = std::max(top, r);
    std::vector<const std::vector<std::size_t>*> close;
    for (const auto& [index, r] : met) {
      if (!(r < top - problem.rough_margin)) close.push_back(&index);
    }
    std::sort(close.begin(), close.end(), [](const auto* x, const auto* y) { return *x < *y; });
    forecast_assignment ranked;
    ranked.room = -1.0;
    for (const std::vector<std::size_t>* index : close) {
      forecast_assignment candidate{*index, problem.room(*index), 0};
      ++evaluations;
      if (ranked.room < 0.0 || better(candidate, ranked)) ranked = std::move(candidate);
    }
    best = std::move(ranked);
  }
  best.evaluations = evaluations;
  return best;
}

}  // namespace mm
