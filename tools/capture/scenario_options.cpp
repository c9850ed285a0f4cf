#include "mm/scenario_options.hpp"

namespace mm::capture {

scenario_file::load_options scenario_options::load_options() const {
  scenario_file::load_options load;
  for (const std::string& text : overrides) load.overrides.push_back(*scenario_file::parse_override(text));
  return load;
}

void add_scenario_options(CLI::App& app, scenario_options& o) {
  const CLI::Validator parameter_override(
      [](std::string& text) -> std::string {
        if (scenario_file::parse_override(text)) return {};
        return "expected NAME=VALUE with a finite number VALUE, got '" + text + "'";
      },
      "");
  app.add_option("SCENARIO", o.scenario, "Scenario file, or the name of a built-in scenario (maneuvermap list)")
      ->required()
      ->type_name("FILE|NAME");
  app.add_option("--agent", o.agent, "Only the plans of this planning vehicle")->type_name("NAME");
  app.add_option("--set", o.overrides, "Override a parameter of the scenario: NAME=VALUE (repeatable)")
      ->check(parameter_override)
      ->allow_extra_args(false)
      ->type_name("NAME=VALUE");
}

}  // namespace mm::capture
