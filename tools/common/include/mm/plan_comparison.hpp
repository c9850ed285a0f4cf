#pragma once

#include <cstddef>

#include "mm/planner.hpp"

namespace mm::plan_comparison {

/// The largest |MI_fast − MI_reference| [-] over the forecast times and both families of two plans
/// of the same input (spec §11), and where it is.
struct index_difference {
  double value = 0.0;
  std::size_t forecast = 0;          ///< index into `forecast_times`
  family which = family::brake;
};

/// Compares the map columns (`mi_brake`, `mi_accelerate`) of two plans with the same forecast grid.
/// Throws std::invalid_argument when the columns differ in length (a map column not computed).
index_difference largest_index_difference(const plan_result& fast, const plan_result& reference);

/// How far the best forecast time of ADJ leads the next one [-]: the largest room max(MI−, MI+) of
/// the forecast times not excluded, less the second largest (1 when fewer than two remain). Where
/// it exceeds 0.02, spec §11 wants the fast planner's τ̄ to be the reference's.
double forecast_time_margin(const plan_result& r);

/// How far the selected family leads the other [-]: |MI−_selected − MI+_selected| under the
/// selected forecast times. Where it exceeds 0.02, spec §11 wants the families to agree.
double family_margin(const plan_result& r);

/// How many of a plan's obstacles are relevant (spec §9: kept by the planner).
std::size_t relevant_obstacles(const plan_result& r);

/// How far the fast planner's pick (τ̄, family) lies below the reference's in the reference's own
/// map column [-]: MI_ref(ī_ref, family_ref) − MI_ref(ī_fast, family_fast), 0 when the picks agree.
/// Spec §11 lets the picks differ where this is at most 0.02. It judges the pick where the map
/// column decides it, i.e. with one relevant obstacle. Throws std::invalid_argument when a pick's
/// forecast index lies outside the reference's map column.
double pick_shortfall(const plan_result& fast, const plan_result& reference);

}  // namespace mm::plan_comparison
