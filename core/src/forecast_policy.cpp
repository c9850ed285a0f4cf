#include "mm/forecast_policy.hpp"

#include <algorithm>

namespace mm {

std::string_view to_string(forecast_policy_kind kind) {
  switch (kind) {
    case forecast_policy_kind::adjustable: return "adj";
    case forecast_policy_kind::constant: return "const";
    case forecast_policy_kind::robust: return "robust";
  }
  return "adj";
}

std::size_t adjustable_forecast_index(std::span<const double> mi_brake, std::span<const double> mi_accelerate,
                                      std::span<const std::uint8_t> excluded) {
  std::size_t best = 0;
  double best_room = -1.0;
  for (std::size_t i = 0; i < mi_brake.size(); ++i) {
    if (excluded[i] != 0) continue;
    const double room = std::max(mi_brake[i], mi_accelerate[i]);
    if (room > best_room + tie_tolerance) {
      best = i;
      best_room = room;
    }
  }
  return best;
}

std::size_t constant_forecast_index(std::span<const double> forecast_times, double forecast_time,
                                    std::span<const std::uint8_t> excluded) {
  std::size_t chosen = 0;
  for (std::size_t i = 0; i < forecast_times.size(); ++i) {
    if (forecast_times[i] <= forecast_time + 1e-9 && excluded[i] == 0) chosen = i;
  }
  return chosen;
}

family select_family(double mi_brake, double mi_accelerate) {
  return mi_brake >= mi_accelerate - tie_tolerance ? family::brake : family::accelerate;
}

}  // namespace mm
