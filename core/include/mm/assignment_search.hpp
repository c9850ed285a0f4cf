#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace mm {

/// How the forecast-time assignment of several obstacles is searched (spec §9).
enum class assignment_search_kind : std::uint8_t {
  coordinate_ascent,  ///< fast: coordinate ascent from two starts
  exhaustive,         ///< reference: every assignment
};

std::string_view to_string(assignment_search_kind kind);

/// The search of spec §9: obstacle j may use forecast index i ∈ candidates[j] (ascending, starting
/// at 0); `room` is max(MI−, MI+) when obstacle j uses index[j] for all j, `room_alone(j, i)` the
/// same with obstacle j alone at index i. Optionally a cheaper estimate of both (`rough_room`,
/// `rough_room_alone`) that the fast search climbs by, before it ranks the assignments whose
/// estimate came within `rough_margin` of the best one by their rooms.
struct assignment_problem {
  std::vector<std::vector<std::size_t>> candidates;
  std::function<double(std::span<const std::size_t> index)> room;
  std::function<double(std::size_t obstacle, std::size_t index)> room_alone;
  std::function<double(std::span<const std::size_t> index)> rough_room;
  std::function<double(std::size_t obstacle, std::size_t index)> rough_room_alone;
  double rough_margin = 0.02;
};

/// A forecast index per obstacle and the room it leaves.
struct forecast_assignment {
  std::vector<std::size_t> forecast_index;
  double room = 1.0;            ///< max(MI−, MI+) under the assignment
  std::size_t evaluations = 0;  ///< calls of `room` and `room_alone` (and of their rough estimates)
};

/// Number of assignments: ∏ |candidates[j]| (saturates at SIZE_MAX).
std::size_t assignment_count(const assignment_problem& problem);

/// Reference (spec §9): every assignment; the largest room wins, ties (within `tie_tolerance`) to
/// the lexicographically smallest index vector (so one obstacle gives the ADJ choice of spec §7).
forecast_assignment exhaustive_assignment_search(const assignment_problem& problem);

/// Fast search (spec §9): coordinate ascent — each obstacle in turn takes its best forecast time
/// with the others fixed, moving only on a strict improvement, until a sweep changes nothing —
/// from two starts: every obstacle at its individually best forecast time, and the best common
/// forecast time (each obstacle capped to its candidates). The better result wins. With a rough
/// room, the ascent climbs by it, and every assignment it met whose rough room is within
/// `rough_margin` of the best is ranked by its room. A problem with one assignment (every obstacle
/// has one candidate) returns it after one call of `room`.
forecast_assignment coordinate_ascent_assignment_search(const assignment_problem& problem);

}  // namespace mm
