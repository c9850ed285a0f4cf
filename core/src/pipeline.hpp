#pragma once

#include <optional>

#include "mm/collision_sets.hpp"
#include "mm/maneuver_samples.hpp"
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

/// The planner's clearance cap (`mm::planner_clearance_cap`).
inline constexpr double clearance_cap = planner_clearance_cap;

/// Smallest step of the continuous-time proof that a command is collision-free [s]
/// (`mm::command_proof_resolution`).
inline constexpr double verification_resolution = command_proof_resolution;

/// What consecutive planning steps of one vehicle share (`mm::planner`): the sampled sets and the
/// ego sweep built on them, kept while the ego's speed, limits and footprint radius, the horizon
/// and the resolution stay those of the step that sampled them.
struct planning_cache {
  maneuver_samples samples;      ///< without node weights and end points (what the fast path reads)
  std::optional<ego_sweep> sweep;  ///< on `samples`
  clearance_field::raster_scratch raster;  ///< the clearance fields' working memory, reused by every step

  /// True when `samples` were sampled for this speed, limits, footprint radius, horizon and resolution.
  bool holds(const ego_state& ego, double horizon, const sampling_resolution& resolution) const;
  /// Records that `samples` were sampled for these.
  void keep(const ego_state& ego, double horizon, const sampling_resolution& resolution);

 private:
  bool valid = false;
  double speed = 0.0;
  ego_limits limits;
  double radius = 0.0;
  double horizon_ = 0.0;
  sampling_resolution resolution_;
};

/// Spec §3–§9 for one planning step; with a `cache` (the fast path only), reusing what the
/// previous step of the same vehicle sampled when that is the same, bit for bit.
plan_result run_pipeline(const plan_input& input, const pipeline_options& options, planning_cache* cache = nullptr);

}  // namespace mm::detail
