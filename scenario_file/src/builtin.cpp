#include "mm/scenario_file/builtin.hpp"

#include <cstddef>

namespace mm::scenario_file {
namespace generated {
extern const builtin_scenario table[];
extern const std::size_t table_size;
}  // namespace generated

std::span<const builtin_scenario> builtin_scenarios() { return {generated::table, generated::table_size}; }

const builtin_scenario* find_builtin(std::string_view name) {
  for (const builtin_scenario& b : builtin_scenarios()) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

}  // namespace mm::scenario_file
