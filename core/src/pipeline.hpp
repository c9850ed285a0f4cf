#pragma once

#include "mm/planner.hpp"

namespace mm::detail {

/// What distinguishes the fast planner from the reference.
struct pipeline_options {
  sampling_resolution resolution;
  double max_time_step = 0.05;  ///< [s], further bounded by the tunneling step of each obstacle
  /// Fast: signed clearances with pruning, MI by interpolating the boundary between samples.
  /// Reference: brute-force collision tests, MI as the safe samples' share of the area.
  bool reference = false;
  assignment_search_kind assignment_search = assignment_search_kind::coordinate_ascent;
  double proof_resolution = 1e-4;  ///< [s] of the reference's continuous-time collision test
};

/// Clearances are clamped to ±this [m] in the fast path: far pairs are skipped, and it is far above
/// how much the clearance changes between neighbouring samples (≈ 0.4 m), so the interpolated
/// boundary is unaffected in practice.
inline constexpr double clearance_cap = 2.0;

/// Smallest step of the continuous-time proof that a command is collision-free [s]: a command
/// passing closer than the largest relative point speed times this is not proven safe (≈ 2–3 cm).
inline constexpr double verification_resolution = 1e-3;

/// Spec §3–§9 for one planning step.
plan_result run_pipeline(const plan_input& input, const pipeline_options& options);

}  // namespace mm::detail
