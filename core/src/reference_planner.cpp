#include "mm/reference_planner.hpp"

#include "pipeline.hpp"

namespace mm {

plan_result plan_reference(const plan_input& input, const reference_resolution& resolution) {
  return detail::run_pipeline(input, {resolution.sampling, resolution.time_step, true, assignment_search_kind::exhaustive});
}

}  // namespace mm
