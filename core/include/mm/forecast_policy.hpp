#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "mm/displacement_set.hpp"

namespace mm {

/// How the forecast time τ̄ is chosen (spec §7).
enum class forecast_policy_kind : std::uint8_t {
  adjustable,  ///< ADJ, the paper's method: the non-excluded τ with the most room
  constant,    ///< a fixed τ, capped at TTC
  /// Robust (an addition spec §7 welcomes): the maneuvers safe under every non-excluded τ of every
  /// obstacle; ADJ when none is (docs/method.md, "The robust policy").
  robust,
};

struct forecast_policy {
  forecast_policy_kind kind = forecast_policy_kind::adjustable;
  double constant_forecast_time = 1.0;  ///< τ [s] of the constant policy; must lie on the forecast grid

  friend bool operator==(const forecast_policy&, const forecast_policy&) = default;
};

std::string_view to_string(forecast_policy_kind kind);

/// Rooms (and indices) closer than this are ties: the spec's tie rules must not depend on the
/// last bits of a floating-point sum, or rotating a scene would change the choice.
inline constexpr double tie_tolerance = 1e-9;

/// ADJ (spec §7): ī = argmax over non-excluded i of f(i) = max(MI−(τ_i), MI+(τ_i)); ties (within
/// `tie_tolerance`) go to the smallest τ. Index 0 is never excluded, so a choice always exists.
std::size_t adjustable_forecast_index(std::span<const double> mi_brake, std::span<const double> mi_accelerate,
                                      std::span<const std::uint8_t> excluded);

/// Constant policy (spec §7): the largest non-excluded i with τ_i ≤ τ (τ capped at TTC).
std::size_t constant_forecast_index(std::span<const double> forecast_times, double forecast_time,
                                    std::span<const std::uint8_t> excluded);

/// Brake-and-steer when MI− ≥ MI+ (ties, within `tie_tolerance`, go to braking), else
/// accelerate-and-steer (spec §7).
family select_family(double mi_brake, double mi_accelerate);

}  // namespace mm
