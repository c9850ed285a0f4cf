// The room to maneuver of one road user of a CommonRoad recording, step by step, from code:
//   02_room_in_recorded_traffic FILE.xml ROAD_USER_ID
// prints, at each recorded step, the time, the road user's speed, the selected forecast time τ̄,
// MI− and MI+ under it, and the planning mode (docs/commonroad.md).
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/reader.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s FILE.xml ROAD_USER_ID\n", argv[0]);
    return 2;
  }
  try {
    mm::commonroad::measure_options options;
    const char* id = argv[2];
    const auto [end, error] = std::from_chars(id, id + std::strlen(id), options.agent);
    if (error != std::errc() || *end != '\0' || options.agent == 0) {
      std::fprintf(stderr, "ROAD_USER_ID %s: expected an obstacle id of the file, a positive integer\n", id);
      return 2;
    }
    const mm::commonroad::scenario recording = mm::commonroad::read_scenario(argv[1]);
    const mm::commonroad::measurement m = mm::commonroad::measure(recording, options);
    std::printf("t_s,speed_mps,tau_bar_s,mi_brake,mi_accel,mode\n");
    for (const mm::commonroad::measured_step& step : m.steps) {
      const mm::plan_result& r = step.result;
      std::printf("%.2f,%.2f,%.3f,%.3f,%.3f,%s\n", step.time, step.ego.speed, r.forecast_time, r.mi_brake_selected,
                  r.mi_accelerate_selected, mm::to_string(r.mode).data());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
