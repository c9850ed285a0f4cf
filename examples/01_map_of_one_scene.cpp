// Prints the Maneuverability Map column of one scene: the ego drives east at 40 km/h, a car
// crosses from the north at 36 km/h, timed to meet it (spec §10, the paper's Fig. 1).
#include <cstdio>

#include "mm/planner.hpp"

int main() {
  mm::plan_input input;
  input.time = 0.0;
  input.ego.pose = {{0.0, 0.0}, 0.0};
  input.ego.speed = 40.0 / 3.6;
  input.nominal = {0.0, 0.0};

  mm::obstacle_track crossing;
  crossing.id = 1;
  const double speed = 36.0 / 3.6;
  for (int k = -50; k <= 0; ++k) {
    const double t = 0.01 * k;
    crossing.history.push_back({t, {{22.0, 20.0 - speed * t}, -1.5707963267948966}, speed});
  }
  input.obstacles.push_back(crossing);

  const mm::plan_result result = mm::plan(input);
  if (!result.ok()) {
    std::fprintf(stderr, "error: %s\n", result.error.c_str());
    return 2;
  }
  std::printf("TTC %.3f s, tau_bar %.3f s, family %s, mode %s, command a = %.2f m/s2, kappa = %.4f 1/m\n",
              result.time_to_collision, result.forecast_time,
              std::string(mm::to_string(result.selected_family)).c_str(),
              std::string(mm::to_string(result.mode)).c_str(), result.command.acceleration,
              result.command.curvature);
  std::printf("%6s %8s %8s %s\n", "tau_s", "MI-", "MI+", "excluded");
  for (std::size_t i = 0; i < result.forecast_times.size(); ++i) {
    std::printf("%6.3f %8.4f %8.4f %s\n", result.forecast_times[i], result.mi_brake[i], result.mi_accelerate[i],
                result.excluded[i] ? "yes" : "");
  }
  return 0;
}
