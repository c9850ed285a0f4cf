#include "mm/plan_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace mm::plan_comparison {

index_difference largest_index_difference(const plan_result& fast, const plan_result& reference) {
  const std::size_t n = reference.forecast_times.size();
  if (fast.mi_brake.size() != n || fast.mi_accelerate.size() != n || reference.mi_brake.size() != n ||
      reference.mi_accelerate.size() != n) {
    throw std::invalid_argument("largest_index_difference: both plans need the map column of every forecast time "
                                "(config.map_column)");
  }
  index_difference worst;
  for (std::size_t i = 0; i < n; ++i) {
    const double brake = std::abs(fast.mi_brake[i] - reference.mi_brake[i]);
    const double accelerate = std::abs(fast.mi_accelerate[i] - reference.mi_accelerate[i]);
    if (brake > worst.value) worst = {brake, i, family::brake};
    if (accelerate > worst.value) worst = {accelerate, i, family::accelerate};
  }
  return worst;
}

double forecast_time_margin(const plan_result& r) {
  std::vector<double> rooms;
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    if (!r.excluded[i]) rooms.push_back(std::max(r.mi_brake[i], r.mi_accelerate[i]));
  }
  std::sort(rooms.rbegin(), rooms.rend());
  return rooms.size() < 2 ? 1.0 : rooms[0] - rooms[1];
}

double family_margin(const plan_result& r) { return std::abs(r.mi_brake_selected - r.mi_accelerate_selected); }

std::size_t relevant_obstacles(const plan_result& r) {
  return static_cast<std::size_t>(
      std::count_if(r.obstacles.begin(), r.obstacles.end(), [](const obstacle_assessment& o) { return o.relevant; }));
}

double pick_shortfall(const plan_result& fast, const plan_result& reference) {
  const auto reference_index = [&](family f, std::size_t i) {
    const std::vector<double>& column = f == family::brake ? reference.mi_brake : reference.mi_accelerate;
    if (i >= column.size()) {
      throw std::invalid_argument("pick_shortfall: forecast index " + std::to_string(i) +
                                  " outside the reference's map column of " + std::to_string(column.size()));
    }
    return column[i];
  };
  if (fast.forecast_index == reference.forecast_index && fast.selected_family == reference.selected_family) return 0.0;
  return reference_index(reference.selected_family, reference.forecast_index) -
         reference_index(fast.selected_family, fast.forecast_index);
}

}  // namespace mm::plan_comparison
