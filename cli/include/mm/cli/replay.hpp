#pragma once

#include <optional>
#include <string>

#include "mm/commonroad/replay.hpp"
#include "mm/commonroad/scenario.hpp"
#include "mm/scenario_file/loader.hpp"

namespace mm::cli {

/// The road user `maneuvermap replay` drives when no `--agent` is given: the recorded ego of the
/// file's first planning problem that has one (`mm::commonroad::recorded_ego`). Throws input_error
/// naming the road users that can be driven when there is none.
std::uint32_t default_replay_agent(const mm::commonroad::scenario& recording);

/// The replay of `recording` (`mm::commonroad::replay_scenario`) as a loaded scenario that
/// `run_scenario` runs and writes: its lanes drawn as roads (each lanelet's centre line, the mean of
/// its bounds, and its mean width), `source` naming the file and the scenario named after it (its stem).
scenario_file::loaded_scenario replay_loaded(const mm::commonroad::scenario& recording,
                                             const mm::commonroad::replay_options& options, const std::string& source);

}  // namespace mm::cli
