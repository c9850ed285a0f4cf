#include "mm/cli/replay.hpp"

#include <filesystem>
#include <string>

#include "mm/cli/commands.hpp"
#include "mm/cli/measure.hpp"

namespace mm::cli {

namespace cr = mm::commonroad;

std::uint32_t default_replay_agent(const cr::scenario& recording) {
  if (const auto ego = planning_problem_ego(recording)) return *ego;
  throw input_error("no planning problem of the file names a recorded road user: give --agent ID, one of: " +
                    cr::measurable_road_users_text(recording));
}

scenario_file::loaded_scenario replay_loaded(const cr::scenario& recording, const cr::replay_options& options,
                                             const std::string& source) {
  scenario_file::loaded_scenario loaded;
  loaded.scenario = cr::replay_scenario(recording, options);
  // Named after the file, as `measure` names its outputs (the library names it by the benchmark id,
  // which need not be the file's name).
  loaded.scenario.name = std::filesystem::path(source).stem().string();
  loaded.source = source;
  for (const cr::lanelet& lane : recording.lanelets) {
    // Bounds of unequal point counts (not written by the converters we know) are left undrawn.
    if (lane.left_bound.size() != lane.right_bound.size() || lane.left_bound.size() < 2) continue;
    scenario_file::road road;
    road.name = "lanelet " + std::to_string(lane.id);
    double width = 0.0;
    for (std::size_t i = 0; i < lane.left_bound.size(); ++i) {
      const vec2 l = lane.left_bound[i];
      const vec2 r = lane.right_bound[i];
      road.centre_line.push_back({(l.x + r.x) / 2.0, (l.y + r.y) / 2.0});
      width += norm(l - r);
    }
    road.width = width / static_cast<double>(lane.left_bound.size());
    loaded.roads.push_back(std::move(road));
  }
  return loaded;
}

}  // namespace mm::cli
