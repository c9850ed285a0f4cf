// Measures the fast planner against the reference planner (spec §11) on random scenes:
// the largest |MI_fast − MI_reference| over forecast times and families, and whether τ̄ and the
// family agree where the two best candidates differ by more than 0.02.
//
//   maneuvermap_accuracy [--scenes N] [--seed S] [--obstacles K] [--noise 0/1] [--fast AxC@DT,...]
//                        [--ref-accelerations A] [--ref-curvatures C] [--ref-proof-resolution S]
//                        [--ref-engine fast|reference [--ref-time-step DT]] [--signs 1]
// With --signs 1 it also compares, per fast setting, which samples collide under each forecast time
// with the reference planner at the same grid (continuous time): the (sample, forecast time) pairs
// the reference finds colliding, those the fast planner misses, and those only the fast one finds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mm/reference_planner.hpp"
#include "random_scenes.hpp"

namespace {

double argument(int argc, char** argv, const char* name, double fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return std::atof(argv[i + 1]);
  }
  return fallback;
}

/// Margin between the best and the second-best candidate of ADJ (by forecast time).
double adj_margin(const mm::plan_result& r) {
  std::vector<double> rooms;
  for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
    if (!r.excluded[i]) rooms.push_back(std::max(r.mi_brake[i], r.mi_accelerate[i]));
  }
  std::sort(rooms.rbegin(), rooms.rend());
  return rooms.size() < 2 ? 1.0 : rooms[0] - rooms[1];
}


struct fast_setting {
  mm::sampling_resolution resolution;
  double time_step;
  double worst = 0.0;
  std::vector<double> errors;
  std::size_t disagreements = 0;
  double seconds = 0.0;
  std::size_t colliding = 0;        ///< (sample, τ) pairs colliding for the reference at this grid
  std::size_t missed = 0;           ///< of those, safe for the fast planner
  std::size_t only_fast = 0;        ///< colliding for the fast planner only
};

/// "11x15@0.05,21x21@0.02" → settings.
std::vector<fast_setting> parse_settings(const std::string& text) {
  std::vector<fast_setting> settings;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    unsigned a = 0;
    unsigned c = 0;
    double dt = 0.0;
    if (std::sscanf(item.c_str(), "%ux%u@%lf", &a, &c, &dt) != 3) {
      std::fprintf(stderr, "bad setting '%s', expected AxC@DT\n", item.c_str());
      std::exit(2);
    }
    fast_setting setting{{a, c}, dt, 0.0, {}, 0, 0.0, 0, 0, 0};
    settings.push_back(std::move(setting));
    start = end + 1;
  }
  return settings;
}

const char* text_argument(int argc, char** argv, const char* name, const char* fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return argv[i + 1];
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const auto scenes = static_cast<std::size_t>(argument(argc, argv, "--scenes", 50));
  const auto seed = static_cast<std::uint64_t>(argument(argc, argv, "--seed", 1));
  mm::testing::scene_options options;
  options.obstacles = static_cast<std::size_t>(argument(argc, argv, "--obstacles", 1));
  options.sensor_noise = argument(argc, argv, "--noise", 0) != 0;
  std::vector<fast_setting> settings = parse_settings(text_argument(argc, argv, "--fast", "11x15@0.05"));
  mm::reference_resolution reference{
      {static_cast<std::size_t>(argument(argc, argv, "--ref-accelerations", 41)),
       static_cast<std::size_t>(argument(argc, argv, "--ref-curvatures", 121))},
      argument(argc, argv, "--ref-proof-resolution", 1e-4)};
  // With --ref-engine fast, the "reference" is the fast planner at the reference grid and this time step.
  const double fast_reference_step = argument(argc, argv, "--ref-time-step", 0.005);

  // --ref-engine fast: compute the "reference" with the fast path at the reference resolution
  // (bit-identical to the reference engine at equal settings, and much cheaper): for convergence studies.
  const bool fast_reference = std::strcmp(text_argument(argc, argv, "--ref-engine", "reference"), "fast") == 0;
  const bool signs = argument(argc, argv, "--signs", 0) != 0;
  std::mt19937_64 rng(seed);
  std::size_t interacting = 0;
  double reference_seconds = 0.0;
  for (std::size_t s = 0; s < scenes; ++s) {
    mm::plan_input in = mm::testing::random_scene(rng, options);
    const auto t0 = std::chrono::steady_clock::now();
    mm::plan_result r;
    if (fast_reference) {
      mm::plan_input fine = in;
      fine.config.resolution = reference.sampling;
      fine.config.max_time_step = fast_reference_step;
      r = mm::plan(fine);
    } else {
      r = mm::plan_reference(in, reference);
    }
    reference_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.ok()) {
      std::fprintf(stderr, "scene %zu: %s\n", s, r.error.c_str());
      return 1;
    }
    bool interacts = false;
    for (std::size_t i = 0; i < r.forecast_times.size(); ++i) {
      interacts = interacts || r.mi_brake[i] < 1.0 || r.mi_accelerate[i] < 1.0;
    }
    interacting += interacts ? 1 : 0;
    for (fast_setting& setting : settings) {
      in.config.resolution = setting.resolution;
      in.config.max_time_step = setting.time_step;
      const auto t1 = std::chrono::steady_clock::now();
      const mm::plan_result f = mm::plan(in);
      setting.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      double scene_worst = 0.0;
      for (std::size_t i = 0; i < f.forecast_times.size(); ++i) {
        scene_worst = std::max({scene_worst, std::abs(f.mi_brake[i] - r.mi_brake[i]),
                                std::abs(f.mi_accelerate[i] - r.mi_accelerate[i])});
      }
      setting.errors.push_back(scene_worst);
      setting.worst = std::max(setting.worst, scene_worst);
      if (adj_margin(r) > 0.02 && (f.forecast_index != r.forecast_index || f.selected_family != r.selected_family)) {
        ++setting.disagreements;
      }
      if (signs) {
        mm::plan_input recorded = in;
        recorded.config.record_samples = true;
        const mm::plan_result fs = mm::plan(recorded);
        const mm::plan_result rs = mm::plan_reference(recorded, {setting.resolution, reference.proof_resolution});
        for (std::size_t i = 0; i < fs.forecast_times.size(); ++i) {
          for (std::size_t m = 0; m < fs.samples->maneuvers.size(); ++m) {
            const bool fast_safe = fs.samples->safe_by_forecast[i][m] != 0;
            const bool reference_safe = rs.samples->safe_by_forecast[i][m] != 0;
            setting.colliding += reference_safe ? 0 : 1;
            setting.missed += !reference_safe && fast_safe ? 1 : 0;
            setting.only_fast += reference_safe && !fast_safe ? 1 : 0;
          }
        }
      }
    }
  }
  std::printf("reference %s %zux%zu: %zu scenes (%zu interacting), %zu obstacle(s), %.1f ms per scene\n",
              fast_reference ? "(fast engine)" : "(reference engine)", reference.sampling.accelerations,
              reference.sampling.curvatures, scenes,
              interacting, options.obstacles, 1e3 * reference_seconds / static_cast<double>(scenes));
  std::printf("%-16s %9s %9s %9s %14s %12s\n", "fast", "max|dMI|", "p95", "median", "disagreements", "ms/scene");
  for (fast_setting& setting : settings) {
    std::sort(setting.errors.begin(), setting.errors.end());
    char name[64];
    std::snprintf(name, sizeof name, "%zux%zu@%g", setting.resolution.accelerations, setting.resolution.curvatures,
                  setting.time_step);
    std::printf("%-16s %9.4f %9.4f %9.4f %14zu %12.3f\n", name, setting.worst,
                setting.errors[setting.errors.size() * 95 / 100], setting.errors[setting.errors.size() / 2],
                setting.disagreements, 1e3 * setting.seconds / static_cast<double>(scenes));
    if (signs) {
      std::printf("%-16s colliding (sample, tau) pairs for the reference at this grid: %zu; missed by the fast planner: %zu; "
                  "colliding for the fast planner only: %zu\n",
                  name, setting.colliding, setting.missed, setting.only_fast);
    }
  }
  return 0;
}
