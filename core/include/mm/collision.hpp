#pragma once

#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "mm/forecast.hpp"
#include "mm/maneuver.hpp"

namespace mm {

/// An obstacle ready for collision tests: its motion estimate and footprint.
struct forecast_obstacle {
  motion_estimate motion;
  footprint shape;
};

/// The time window of the collision test (spec §5).
struct collision_window {
  double horizon = 1.0;    ///< T_h [s]: the maneuver's duration, then straight ahead
  double duration = 3.0;   ///< T_c [s] ≥ T_h
  double time_step = 0.05; ///< sampling step [s] of [0, T_c]
  double margin = 0.0;     ///< safety margin inflating every obstacle [m] (spec §2)
};

inline constexpr double no_collision = std::numeric_limits<double>::infinity();

/// Largest speed [m/s] of the ego's reference point executing `u` over the window: v_max, the larger
/// of the start speed and the speed at T_h (the speed is monotonic in t, then constant).
double largest_speed(const ego_state& ego, const maneuver& u, double horizon);

/// Largest speed [m/s] of any point of the ego footprint executing `u` over the window:
/// v_max (1 + |κ| R).
double largest_point_speed(const ego_state& ego, const maneuver& u, double horizon);

/// The same from the reference point's largest speed [m/s], the curvature [1/m] and the footprint's
/// bounding radius [m]: v_max (1 + |κ| R).
double largest_point_speed(double largest_speed, double curvature, double radius);

/// Largest speed [m/s] of any point of the obstacle's footprint under any forecast: v + |ω| R.
double largest_point_speed(const forecast_obstacle& obstacle);

/// The sample times k·step, k = 0..K, of [0, duration], the last one equal to `duration`.
std::vector<double> sample_times(double duration, double step);

/// The largest relative speed of the ego and `obstacle` within the window [m/s] (spec §5): the ego's
/// top speed, v0 accelerated at a_max until T_h and capped at v_cap, plus the obstacle's speed.
double tunneling_relative_speed(const ego_state& ego, const forecast_obstacle& obstacle,
                                const collision_window& window);

/// Largest time step [s] at which the ego and `obstacle` cannot pass through each other between
/// samples (spec §5): the smallest footprint dimension over `tunneling_relative_speed`.
double tunneling_time_step(const ego_state& ego, const forecast_obstacle& obstacle,
                           const collision_window& window);

/// The shortest collision time step the planner takes [s]: 0.1 ms, 30,000 sample times over a
/// 3 s window. An input whose tunneling bound lies below it (footprints of micrometres, speeds
/// far beyond any road user's) is refused as invalid (docs/method.md, deviations).
inline constexpr double smallest_collision_time_step = 1e-4;

/// Smallest step of the planner's continuous-time proof that a command is collision-free [s]
/// (`verified_collision_free`, docs/method.md §4.5): by the speed bound, a command passing closer
/// than the largest relative point speed L times this (L × 1 ms: 7 mm at L = 7 m/s, 2–3 cm at
/// 20–30 m/s) is not proven safe; the translation bound, the planner's second try, proves such
/// passes where the two bodies' distance changes slowly (side by side).
inline constexpr double command_proof_resolution = 1e-3;

/// The longest step the proof's translation bound tries [s] (`verified_collision_free`).
inline constexpr double longest_translated_step = 0.025;

/// The first sample time at which the ego executing `u` overlaps one of `obstacles`, obstacle j
/// following its forecast with forecast time `forecast_times[j]`; `no_collision` if none (spec §5).
/// Sample times at which an obstacle cannot overlap yet (bounding discs apart by more than the
/// largest speeds close in the time between) are not looked at for it: equal to
/// `first_collision_time_reference`, bit for bit.
double first_collision_time(const ego_state& ego, const maneuver& u,
                            std::span<const forecast_obstacle> obstacles,
                            std::span<const double> forecast_times, const collision_window& window);

/// `first_collision_time` of every maneuver of `maneuvers`, bit for bit, with each obstacle's
/// forecast placed once per sample time for all of them.
std::vector<double> first_collision_times(const ego_state& ego, std::span<const maneuver> maneuvers,
                                          std::span<const forecast_obstacle> obstacles,
                                          std::span<const double> forecast_times, const collision_window& window);

/// The reference for `first_collision_time`: every obstacle at every sample time.
double first_collision_time_reference(const ego_state& ego, const maneuver& u,
                                      std::span<const forecast_obstacle> obstacles,
                                      std::span<const double> forecast_times, const collision_window& window);

/// True when `first_collision_time` is finite: the maneuver collides [CSS].
bool maneuver_collides(const ego_state& ego, const maneuver& u,
                       std::span<const forecast_obstacle> obstacles,
                       std::span<const double> forecast_times, const collision_window& window);

/// A new running minimum moves the argmin only when it is lower by more than this [m], so that the
/// refinement does not depend on the last bits of two nearly equal samples.
inline constexpr double argmin_tolerance = 1e-9;

/// Running minimum of a sampled clearance and where it was reached: `update` with the samples in
/// time order. The argmin moves to a new sample only when that is lower by more than
/// `argmin_tolerance` than the sample at the argmin.
struct running_minimum {
  double value = std::numeric_limits<double>::infinity();
  double at_argmin = std::numeric_limits<double>::infinity();
  std::size_t argmin = 0;

  void update(double d, std::size_t k) {
    value = std::min(value, d);
    if (at_argmin - d > argmin_tolerance) {
      at_argmin = d;
      argmin = k;
    }
  }
};

/// Evaluation points of `refined_minimum` lie on a grid of this many steps across its bracket
/// (1.6 ms at the default step; 512 steps left the worst |ΔMI| of docs/method.md §7 the same to the
/// fourth decimal and cost ADJ runs 8 % more time).
inline constexpr double refinement_grid = 64.0;

/// The continuous-time minimum of a signed clearance sampled at `times`, refined around the argmin
/// `k` of its samples (`running_minimum`), where it takes `at_sample` = at(t_k) [m]: Brent's search
/// for the minimum of `at(t)` on [t_{k−1}, t_{k+1}] ([t_0, t_1] at the window's start) — a parabola through the three best points
/// where it moves the bracket fast enough, a golden-section step where it does not — until the
/// minimum is bracketed to a grid step, at most `max_evaluations` calls. Every point is rounded to
/// a grid of `refinement_grid` steps across the bracket, so that two scenes equal up to rounding
/// (one moved or mirrored) are evaluated at the same times and refine to the same value. The
/// result is the smallest value seen, `at_sample` included: a value the clearance really takes, so
/// never below the true minimum. At the window's end, `at_sample`.
template <class At>
double refined_minimum(std::span<const double> times, std::size_t k, At&& at, double at_sample,
                       int max_evaluations = 16) {
  if (k + 1 >= times.size()) return at_sample;
  constexpr double golden = 0.3819660112501051;  // (3 − √5)/2
  const double origin = times[k == 0 ? 0 : k - 1];
  const double grid = (times[k + 1] - origin) / refinement_grid;
  const double tolerance = grid;
  const auto on_grid = [&](double t) { return origin + std::round((t - origin) / grid) * grid; };
  double lo = origin;
  double hi = times[k + 1];
  // x: best point so far; w: second best; v: the previous w. step: the last move; older: the one before.
  double x = times[k];
  double w = x;
  double v = x;
  double fx = at_sample;
  double fw = fx;
  double fv = fx;
  double step = 0.0;
  double older = 0.0;
  for (int evaluation = 0; evaluation < max_evaluations; ++evaluation) {
    const double mid = 0.5 * (lo + hi);
    if (std::abs(x - mid) <= 2.0 * tolerance - 0.5 * (hi - lo)) break;
    bool parabolic = false;
    if (std::abs(older) > tolerance) {
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      // Accept the parabola's vertex when it lies inside the bracket and moves less than half the
      // step before last (otherwise the parabola is not converging).
      if (std::abs(p) < std::abs(0.5 * q * older) && p > q * (lo - x) && p < q * (hi - x)) {
        older = step;
        step = p / q;
        const double u = x + step;
        if (u - lo < 2.0 * tolerance || hi - u < 2.0 * tolerance) step = x < mid ? tolerance : -tolerance;
        parabolic = true;
      }
    }
    if (!parabolic) {
      older = (x < mid ? hi : lo) - x;
      step = golden * older;
    }
    double u = on_grid(std::abs(step) >= tolerance ? x + step : x + (step > 0.0 ? tolerance : -tolerance));
    if (u == x) u = on_grid(x + (step > 0.0 ? grid : -grid));
    if (u <= lo || u >= hi) break;
    const double fu = at(u);
    if (fu <= fx) {
      (u < x ? hi : lo) = x;
      v = w;
      fv = fw;
      w = x;
      fw = fx;
      x = u;
      fx = fu;
    } else {
      (u < x ? lo : hi) = u;
      if (fu <= fw || w == x) {
        v = w;
        fv = fw;
        w = u;
        fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u;
        fv = fu;
      }
    }
  }
  return fx;
}

/// How the continuous-time proof of a command steps (`verified_collision_free`, docs/method.md §4.5).
enum class proof_steps : std::uint8_t {
  /// c / L only: a command passing within about L × resolution of the margin (1–3 cm at 1 ms) is
  /// not proven, which keeps that much more from the forecasts where it is.
  speed_bound,
  /// The longer of c / L and the translation bound: passes side by side are proven down to the
  /// margin. The planner's second try, before a near-crash.
  translation_bound,
};

/// True when the ego executing `u` provably keeps more than the margin from every obstacle
/// (obstacle j forecast with `forecast_times[j]`) at every time in [0, T_c], not only at sample
/// times. Conservative advancement: each step is proven free of contact by
/// - the speed bound: the signed distance changes no faster than L, the largest relative speed of
///   any two footprint points, so from a clearance c > 0 at time t no contact is possible before
///   t + c/L;
/// - with `proof_steps::translation_bound`, also (the longer step of the two) the translation
///   bound: over [t, t + h] each footprint stays within its placement at t moved at its velocity at
///   t, widened by R·ω·s + A·s²/2 (R its bounding radius, ω and A bounds of its turn rate and of its
///   acceleration), so no contact is possible before t + h when the two moved placements keep more
///   than the margin plus both widenings over [0, h] (a translation, in closed form); tried for
///   h = min(`longest_translated_step`, T_c − t)·2^−k above c/L. Bodies passing side by side, whose
///   distance changes far slower than L, are so proven in steps of about c/(R_e ω_e + R_o ω_o)
///   instead of c/L; two that go straight, in one step.
/// Stepping so across the window proves it; a step shorter than `resolution` [s] counts as not
/// proven, unless it reaches T_c.
///
/// Obstacles whose bounding discs are so far apart from the ego's that their clearance can neither
/// be ≤ 0 nor shorten the step are not asked for their distance: equal to
/// `verified_collision_free_reference`, which asks every obstacle at every step.
bool verified_collision_free(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                             std::span<const double> forecast_times, const collision_window& window,
                             double resolution = 1e-3, proof_steps steps = proof_steps::speed_bound);

/// The reference for `verified_collision_free`: the signed distance of every obstacle at every step.
bool verified_collision_free_reference(const ego_state& ego, const maneuver& u,
                                       std::span<const forecast_obstacle> obstacles,
                                       std::span<const double> forecast_times, const collision_window& window,
                                       double resolution = 1e-3, proof_steps steps = proof_steps::speed_bound);

/// Time resolution of `time_to_collision` [s].
inline constexpr double time_to_collision_resolution = 1e-4;

/// Time to collision [s] (spec §6): the first time the ego holding `nominal` (its §5 trajectory)
/// comes within the margin of `obstacle` following its CTRV forecast for the whole window, in
/// continuous time; `no_collision` if none within T_c. Conservative advancement: from a time at
/// which the signed distance − margin is d > 0 none can occur for d / L, L the sum of both
/// footprints' largest point speeds; it stops where d ≤ 0, or where the next step would be shorter
/// than `time_to_collision_resolution` (a graze within L × 10⁻⁴ m counts as a contact). So no
/// contact lies before the result, and a contact shorter than any time step is found: the result
/// does not depend on the collision time step.
double time_to_collision(const ego_state& ego, const maneuver& nominal,
                         const forecast_obstacle& obstacle, const collision_window& window);

/// The reference for `time_to_collision`: the first time of a grid of `time_to_collision_resolution`
/// over the window at which the two overlap (signed distance − margin ≤ 0), or `no_collision`.
/// `time_to_collision` is never later, and is within L × 10⁻⁴ m of a contact.
double time_to_collision_reference(const ego_state& ego, const maneuver& nominal,
                                   const forecast_obstacle& obstacle, const collision_window& window);

}  // namespace mm
