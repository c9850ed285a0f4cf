// A controller of your own drives a planning vehicle in the simulator while its planner keeps
// measuring its room to maneuver (docs/simulator.md §1, `override_command`):
//   03_controller_in_the_loop
// runs the built-in S1 twice — A driven by its own planner, then by a late driver that keeps its lane
// and speed and brakes at 3 m/s² only while the time to collision its planner reports is below
// 1.5 s — and prints, for each, how A's run ended and the least room max(MI−, MI+) its planner saw:
// the driver gets by B without a crash, but with no room left on the way.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>

#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"

namespace {

struct outcome {
  mm::sim::run_metrics metrics;
  double least_room = 1.0;  ///< max(MI−, MI+) under τ̄, the least over the run's plans
};

/// Runs S1; with `driver`, A takes the driver's command at every step instead of its own.
outcome run_s1(bool driver) {
  mm::sim::simulation sim(mm::scenario_file::load("s1-crossing").scenario);
  const mm::sim::agent_id a = *sim.find("A");
  outcome out;
  while (!sim.ended()) {
    if (const mm::sim::plan_record* plan = sim.last_plan(a); plan != nullptr && sim.planned_now(a)) {
      out.least_room = std::min(out.least_room, std::max(plan->result.mi_brake_selected,
                                                         plan->result.mi_accelerate_selected));
      if (driver && sim.state(a).status == mm::sim::agent_status::active) {
        const std::optional<mm::plan_input> seen = sim.planning_input(a);
        const double brake = plan->result.time_to_collision < 1.5 ? -3.0 : 0.0;
        sim.override_command(a, {brake, seen->nominal.curvature});  // u_nom's curvature: keeps its lane
      }
    }
    sim.step();
  }
  out.metrics = sim.metrics(a);
  return out;
}

void print(const char* who, const outcome& o) {
  const mm::sim::run_metrics& m = o.metrics;
  if (m.crash) {
    std::printf("%-8s crash at %.2f s with %s; least room %.3f\n", who, *m.crash_time_s, m.crash_with.c_str(),
                o.least_room);
  } else {
    std::printf("%-8s no crash, closest %.2f m to %s, slowest %.1f km/h; least room %.3f\n", who, *m.min_dist_m,
                m.closest_agent.c_str(), m.min_speed_kmh, o.least_room);
  }
}

}  // namespace

int main() {
  try {
    print("planner", run_s1(false));
    print("driver", run_s1(true));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
