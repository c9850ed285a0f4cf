#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// Which rule of spec §8 produced the command.
enum class planning_mode : std::uint8_t {
  nominal,     ///< §8.1: the nominal maneuver is safe
  avoid,       ///< §8.2: the safe maneuver of minimal effort
  urgent,      ///< §8.3: urgent steering, the safe maneuver of maximal effort
  near_crash,  ///< §8.4: nothing is safe; the latest first collision
};

std::string_view to_string(planning_mode mode);

/// Effort weights of J (spec §8).
struct effort_weights {
  double longitudinal = 1.0;  ///< w_lon [s⁴/m²]
  double lateral = 1.0;       ///< w_lat [s⁴/m²]

  friend bool operator==(const effort_weights&, const effort_weights&) = default;
};

/// J(u) = w_lon (a − a_nom)² + w_lat (v0² (κ − κ_nom))² [m²/s⁴] (spec §8): the squared change of
/// longitudinal and lateral acceleration.
double maneuver_effort(const maneuver& u, const maneuver& nominal, double initial_speed, const effort_weights& weights);

/// What the maneuver choice needs to know.
struct choice_input {
  const maneuver_samples* samples = nullptr;
  const sample_mask* colliding = nullptr;  ///< colliding samples under the selected forecast
  family selected_family = family::brake;  ///< from the forecast-time selection (§7)
  maneuver nominal;                        ///< u_nom, within the limits
  bool nominal_safe = false;               ///< u_nom does not collide under the selected forecast
  double initial_speed = 0.0;              ///< v0 [m/s]
  effort_weights weights;
  bool urgent_steering = false;            ///< the scenario option of §8.3
  /// Proves a candidate collision-free in continuous time; candidates that fail are passed over.
  /// Empty: every candidate outside `colliding` is taken as safe.
  std::function<bool(const maneuver&)> verify;
};

struct maneuver_decision {
  maneuver command;
  planning_mode mode = planning_mode::nominal;
  std::optional<std::size_t> sample;  ///< the chosen sample; none for the nominal maneuver
};

/// Rules 1–3 of spec §8. Candidates of a family are its grid and its nominal-curvature column.
/// 1. u_nom if safe; 2. the safe candidate of minimal J in the selected family, else in the
/// other; 3. with urgent steering, when no nominal-curvature candidate of either family is safe,
/// maximal J instead. Ties in J go to the smaller steering change |κ − κ_nom|, then to the
/// smaller acceleration change, then to the first sample. Candidates are taken in that order
/// until one passes `verify`. Nothing when no candidate is safe and verified (rule 4).
std::optional<maneuver_decision> choose_maneuver(const choice_input& input);

/// Rule 4 of spec §8 (near-crash): the sample of latest first collision time
/// (`first_collision[m]`, ∞ for none), ties to stronger braking, then to the latest first contact
/// of the bodies without the safety margin (`first_contact[m]`, ∞ for none), then to the smaller
/// steering change from `nominal_curvature`, then to the first sample. Only the values of
/// `first_contact` at the samples the first two keys leave tied matter. The last two keys are
/// additions to spec §8 (docs/method.md §5): inside the margin every maneuver collides at t = 0,
/// and the steering change alone would brake along the nominal curvature, into the obstacle when
/// the path leads there.
maneuver_decision near_crash_maneuver(const maneuver_samples& samples, std::span<const double> first_collision,
                                      std::span<const double> first_contact, double nominal_curvature);

}  // namespace mm
