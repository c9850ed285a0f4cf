#pragma once

#include "mm/planner.hpp"

namespace mm::detail {

/// What distinguishes the fast planner from the reference: how finely it samples and how it
/// computes collision sets and the forecast-time assignment.
struct pipeline_options {
  sampling_resolution resolution;
  double max_time_step = 0.05;  ///< [s], further bounded by the tunneling step of each obstacle
  bool brute_force_collision_sets = false;
  assignment_search_kind assignment_search = assignment_search_kind::coordinate_ascent;
};

/// Spec §3–§9 for one planning step.
plan_result run_pipeline(const plan_input& input, const pipeline_options& options);

}  // namespace mm::detail
