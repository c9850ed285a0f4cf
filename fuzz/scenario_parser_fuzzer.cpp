// libFuzzer target for the scenario loader: any input must either load or be rejected with a
// scenario_error (located, with a message). A scenario that loads must also make a simulation and
// step (the loader's checks are the simulator's: a scenario it accepts that the simulator refuses
// is a bug); small ones are stepped a few times, planning included. Every scenario that loads is
// written back (`scenario_text`, which loads its own text and throws std::logic_error unless it reads
// back bit for bit): a scenario that loads but cannot be written is a bug, and so is a roundabout
// whose lanes cannot be drawn as a CommonRoad recording draws them. Any other exception, a
// crash, a leak or a hang is a bug. Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "mm/scenario_file/loader.hpp"
#include "mm/scenario_file/writer.hpp"
#include "mm/sim/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mm::scenario_file::loaded_scenario loaded = mm::scenario_file::load_text(text, "fuzz.yaml");
    const mm::sim::scenario& sc = loaded.scenario;
    (void)mm::scenario_file::scenario_text(loaded);
    if (loaded.roundabout) {
      // Its lanes as a CommonRoad recording writes them: finite, linked within the list.
      const std::vector<mm::sim::lane_edges> lanes = mm::scenario_file::lane_network(*loaded.roundabout);
      for (const mm::sim::lane_edges& lane : lanes) {
        if (lane.left.size() < 2 || lane.left.size() != lane.right.size()) __builtin_trap();
        for (const mm::vec2 p : lane.left) {
          if (!std::isfinite(p.x) || !std::isfinite(p.y)) __builtin_trap();
        }
        for (const std::size_t next : lane.successors) {
          if (next >= lanes.size()) __builtin_trap();
        }
      }
    }
    const std::size_t agents =
        sc.planning_vehicles.size() + sc.scripted_vehicles.size() + sc.pedestrians.size() + sc.static_obstacles.size();
    if (agents > 12) return 0;  // the fuzzer's time goes to inputs, not to planning crowds
    mm::sim::simulation sim(sc);
    for (int k = 0; k < 3 && !sim.ended(); ++k) sim.step();
  } catch (const mm::scenario_file::scenario_error& e) {
    // Every rejection must say something.
    if (e.problem().empty()) __builtin_trap();
  }
  return 0;
}
