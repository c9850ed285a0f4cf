// libFuzzer target for the CommonRoad reader: any input must either read or be rejected with a
// read_error that says something; what it reads must give a planning input of its first road user
// at its last state, or be refused with a measure_error, and the planner must plan on that input
// (indices in [0, 1]) or refuse it with a status, under ADJ and under the robust policy alike; and
// its replay with that road user driven by the planner must be a valid simulation that takes a few
// steps, or be refused with a measure_error. Every scenario that reads must also be written
// (`scenario_xml`, which reads its own text back and throws unless it is the same scenario).
// Any other exception, a crash, a leak or a hang is a bug.
// Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/reader.hpp"
#include "mm/commonroad/replay.hpp"
#include "mm/commonroad/writer.hpp"
#include "mm/sim/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mm::commonroad::scenario s = mm::commonroad::read_scenario_text(text, "fuzz.xml");
    (void)mm::commonroad::scenario_xml(s);
    const std::vector<std::uint32_t> users = mm::commonroad::measurable_road_users(s);
    if (users.empty()) return 0;
    mm::commonroad::measure_options options;
    options.agent = users.front();
    const mm::commonroad::obstacle* agent = nullptr;
    for (const mm::commonroad::obstacle& o : s.obstacles) {
      if (o.id == options.agent) agent = &o;
    }
    const mm::plan_input in = mm::commonroad::planning_input(s, options, agent->states.back().step);
    const mm::plan_result r = mm::plan(in);
    if (r.ok() && !(r.mi_brake_selected >= 0.0 && r.mi_brake_selected <= 1.0)) __builtin_trap();
    mm::plan_input robust = in;
    robust.config.policy.kind = mm::forecast_policy_kind::robust;
    const mm::plan_result rr = mm::plan(robust);
    if (rr.ok() != r.ok() || (rr.ok() && !(rr.mi_accelerate_selected >= 0.0 && rr.mi_accelerate_selected <= 1.0))) {
      __builtin_trap();
    }
    mm::commonroad::replay_options replay;
    replay.agent = options.agent;
    mm::sim::simulation sim(mm::commonroad::replay_scenario(s, replay));
    for (int k = 0; k < 5 && !sim.ended(); ++k) sim.step();
  } catch (const mm::commonroad::read_error& e) {
    if (std::string_view(e.what()).empty()) __builtin_trap();
  } catch (const mm::commonroad::measure_error& e) {
    if (std::string_view(e.what()).empty()) __builtin_trap();
  }
  return 0;
}
