#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm::sim {

/// Side on which a planning vehicle passed the agent it came closest to (spec §12).
enum class bypass_side : std::uint8_t { none, left, right };

std::string_view to_string(bypass_side side);

/// The run metrics of one planning vehicle (spec §12, the paper's Table 1 columns), measured on
/// the true states at every simulation step while the vehicle is in the world and has neither
/// crashed nor finished; "the moment of smallest gap" is the first step at which the smallest gap
/// of the run occurred (the crash step on a crash).
struct run_metrics {
  std::string agent;                     ///< the planning vehicle's name
  bool crash = false;                    ///< its footprint overlapped another agent's at some step
  std::optional<double> crash_time_s;    ///< time of the first overlap [s]
  std::string crash_with;                ///< name of the agent it crashed into ("" without crash)
  /// Smallest gap between its footprint and any other agent's over the run [m], 0 on a crash;
  /// none when no other agent was ever in the world.
  std::optional<double> min_dist_m;
  std::optional<double> min_dist_time_s;  ///< the moment of smallest gap [s]
  std::string closest_agent;              ///< name of the agent at the smallest gap
  /// TTC [s] at the moment of smallest gap: the first time the two footprints would overlap if
  /// both kept their velocity vectors (constant velocity, fixed headings). None on a crash, or if
  /// they would never meet.
  std::optional<double> ttc_at_min_s;
  /// Its speed [km/h] at the crash, otherwise at the moment of smallest gap.
  std::optional<double> speed_kmh;
  /// Sign of its lateral offset from its reference path at the moment of smallest gap (left
  /// positive); `none` if |offset| never exceeded 0.1 m over the run.
  bypass_side bypass = bypass_side::none;
  double lateral_offset_at_min_m = 0.0;  ///< the offset behind `bypass` [m]
  double max_lateral_offset_m = 0.0;     ///< largest |offset| over the run [m]
  double min_speed_kmh = 0.0;            ///< over the run [km/h]
  double max_speed_kmh = 0.0;            ///< over the run [km/h]
  /// Time [s] spent under a non-nominal planning mode (spec §8 rules 2–4) whose selected family
  /// (spec §7) is brake-and-steer, resp. accelerate-and-steer.
  double time_in_brake_s = 0.0;
  double time_in_accel_s = 0.0;
  std::size_t planning_steps = 0;        ///< calls of `mm::plan`
  /// Wall-clock time of one `mm::plan` call [µs] (steady clock): median and 99th percentile
  /// (nearest rank). 0 unless `run_options::measure_cpu_time`.
  double cpu_median_us = 0.0;
  double cpu_p99_us = 0.0;
};

/// Time to collision under constant velocity [s]: the first t ≥ 0 at which `a` placed at
/// p_a + t·v_a overlaps `b` placed at p_b + t·v_b (headings fixed), located to 1e-6 s; 0 if they
/// overlap now; none if they never do. Exact up to that tolerance: the gap between two convex
/// shapes in relative uniform translation is a convex function of t, so its minimum is found by
/// golden-section search and the first contact by bisection before it.
std::optional<double> constant_velocity_ttc(const mm::footprint& a, const mm::pose& pose_a, vec2 velocity_a,
                                            const mm::footprint& b, const mm::pose& pose_b, vec2 velocity_b);

/// The q-quantile (0 < q ≤ 1) by the nearest-rank method: the ⌈q·n⌉-th smallest value; for the
/// median (q = 0.5) of an even count, the mean of the two middle values. 0 for no values.
double quantile(std::span<const double> values, double q);

}  // namespace mm::sim
