#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// How the forecast-time assignment of several obstacles is searched (spec §9).
enum class assignment_search_kind : std::uint8_t {
  coordinate_ascent,  ///< fast: coordinate ascent from two starts
  exhaustive,         ///< reference: every assignment
};

std::string_view to_string(assignment_search_kind kind);

/// The search space of spec §9: obstacle j may use forecast index i ∈ candidates[j]; its
/// collision set under τ_i is collision_sets[j][i]. The safe sets are the samples outside the
/// union of the chosen collision sets.
struct assignment_problem {
  const maneuver_samples* samples = nullptr;
  std::vector<std::vector<sample_mask>> collision_sets;  ///< [obstacle][forecast index]
  std::vector<std::vector<std::size_t>> candidates;      ///< [obstacle] allowed indices, ascending, non-empty
};

/// A forecast index per obstacle and the room it leaves.
struct forecast_assignment {
  std::vector<std::size_t> forecast_index;
  double room = 1.0;             ///< max(MI−, MI+) of the union of the chosen collision sets
  std::size_t evaluations = 0;   ///< assignments whose room was computed
};

/// The union of the collision sets chosen by `forecast_index`.
sample_mask colliding_under(const assignment_problem& problem, std::span<const std::size_t> forecast_index);

/// max(MI−, MI+) under the assignment: the objective of the search.
double assignment_room(const assignment_problem& problem, std::span<const std::size_t> forecast_index);

/// Number of assignments of the problem: ∏ |candidates[j]| (saturates at SIZE_MAX).
std::size_t assignment_count(const assignment_problem& problem);

/// Reference (spec §9): every assignment; the largest room wins, ties to the lexicographically
/// smallest index vector (so one obstacle gives the ADJ choice of spec §7).
forecast_assignment exhaustive_assignment_search(const assignment_problem& problem);

/// Fast search (spec §9): coordinate ascent (each obstacle in turn takes its best forecast time
/// with the others fixed, until no obstacle improves) from two starts: every obstacle at its
/// individually best forecast time, and the best common forecast time. The better result wins.
forecast_assignment coordinate_ascent_assignment_search(const assignment_problem& problem);

}  // namespace mm
