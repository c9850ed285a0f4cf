#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "mm/scenario_file/loader.hpp"

namespace mm::capture {

/// A scenario and its planning vehicles on a developer tool's command line: SCENARIO (a built-in
/// name or a file), --agent NAME (only that planning vehicle) and --set NAME=VALUE (parameter
/// overrides, each checked when parsed).
struct scenario_options {
  std::string scenario;
  std::string agent;
  std::vector<std::string> overrides;

  /// The overrides as the loader takes them.
  scenario_file::load_options load_options() const;
};

/// Adds SCENARIO, --agent and --set to `app`, stored in `o`.
void add_scenario_options(CLI::App& app, scenario_options& o);

}  // namespace mm::capture
