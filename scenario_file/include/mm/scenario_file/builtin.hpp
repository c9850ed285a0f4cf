#pragma once

#include <span>
#include <string_view>

namespace mm::scenario_file {

/// A scenario file compiled into the binary from `scenarios/NAME.yaml`.
struct builtin_scenario {
  std::string_view name;  ///< the file's stem, e.g. `s2-roundabout`
  std::string_view text;  ///< the file's bytes
};

/// Every built-in scenario, sorted by name.
std::span<const builtin_scenario> builtin_scenarios();

/// The built-in scenario called `name`, or null.
const builtin_scenario* find_builtin(std::string_view name);

}  // namespace mm::scenario_file
