#include "mm/reference_planner.hpp"

#include "pipeline.hpp"

namespace mm {

plan_result plan_reference(const plan_input& input, const reference_resolution& resolution) {
  return detail::run_pipeline(input, {resolution.sampling, 0.01, true, assignment_search_kind::exhaustive,
                                      resolution.proof_resolution});
}

}  // namespace mm
