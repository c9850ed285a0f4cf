// Measures the fast planner against the reference planner (spec §11) on random scenes:
// the largest |MI_fast − MI_reference| over forecast times and families, and the disagreements of
// the pick (τ̄, family): with one relevant obstacle a fast pick more than 0.02 below the
// reference's in the reference's own indices; with several, τ̄ or the family differing where the
// reference's best forecast time leads by more than 0.02.
//
//   maneuvermap_accuracy [--scenes N] [--seed S] [--obstacles K] [--noise 0/1] [--fast AxC@DT,...]
//                        [--ref-accelerations A] [--ref-curvatures C] [--ref-accelerations-1d A]
//                        [--ref-proof-resolution S]
//                        [--ref-engine fast|reference [--ref-time-step DT]] [--signs 1]
// With --signs 1 it also compares, per fast setting, which samples collide under each forecast time
// with the reference planner at the same grid (continuous time): the (sample, forecast time) pairs
// the reference finds colliding, those the fast planner misses, and those only the fast one finds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mm/plan_comparison.hpp"
#include "mm/reference_planner.hpp"
#include "mm/tool_cli.hpp"
#include "random_scenes.hpp"

namespace {

/// Spec §11's bound on |MI_fast − MI_reference|, and on how far below the reference's a pick may lie.
constexpr double accuracy_bound = 0.02;

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
  /// As on the command line: AxC@DT.
  std::string label() const {
    char name[64];
    std::snprintf(name, sizeof name, "%zux%zu@%g", resolution.accelerations, resolution.curvatures, time_step);
    return name;
  }
};

/// One AxC@DT entry of --fast: none when malformed or out of range.
std::optional<fast_setting> parse_setting(std::string_view item) {
  const std::size_t at = item.find('@');
  if (at == std::string_view::npos) return std::nullopt;
  const auto grid = mm::tool_cli::parse_grid(item.substr(0, at));
  const auto dt = mm::tool_cli::parse_real(item.substr(at + 1));
  if (!grid || !dt || !(*dt > 0.0)) return std::nullopt;
  return fast_setting{*grid, *dt, 0.0, {}, 0, 0.0, 0, 0, 0};
}

/// "11x15@0.05,21x21@0.02" → settings; the error names the first bad entry.
std::vector<fast_setting> parse_settings(std::string_view text, std::string* error = nullptr) {
  std::vector<fast_setting> settings;
  std::size_t start = 0;
  for (std::size_t index = 1;; ++index) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string_view item = text.substr(start, end - start);
    std::optional<fast_setting> setting = parse_setting(item);
    if (!setting) {
      if (error != nullptr) {
        *error = "entry " + std::to_string(index) + " '" + std::string(item) + "' of '" + std::string(text) +
                 "': expected AxC@DT, A accelerations from 2 to 2001, C curvatures from 1 to 2001, "
                 "DT a time step > 0 [s], e.g. 11x15@0.05";
      }
      return {};
    }
    settings.push_back(std::move(*setting));
    if (end == text.size()) return settings;
    start = end + 1;
  }
}

CLI::Validator fast_settings() {
  return CLI::Validator(
      [](std::string& text) {
        std::string error;
        parse_settings(text, &error);
        return error;
      },
      "");
}

/// The command line; the defaults are the tool's.
struct accuracy_options {
  std::size_t scenes = 50;
  std::uint64_t seed = 1;
  mm::testing::scene_options scene;
  std::string fast = "11x15@0.05";
  mm::reference_resolution reference{{41, 121}, 1e-4};
  /// "fast": the "reference" is the fast planner at the reference grid and `reference_time_step`
  /// (bit-identical to the reference engine at equal settings, and much cheaper): for convergence studies.
  std::string engine = "reference";
  double reference_time_step = 0.005;
  bool signs = false;
};

int measure(const accuracy_options& o) {
  const std::size_t scenes = o.scenes;
  const mm::testing::scene_options& options = o.scene;
  const mm::reference_resolution& reference = o.reference;
  std::vector<fast_setting> settings = parse_settings(o.fast);
  const bool fast_reference = o.engine == "fast";
  const bool signs = o.signs;
  std::mt19937_64 rng(o.seed);
  std::size_t interacting = 0;
  double reference_seconds = 0.0;
  for (std::size_t s = 0; s < scenes; ++s) {
    mm::plan_input in = mm::testing::random_scene(rng, options);
    const auto t0 = std::chrono::steady_clock::now();
    mm::plan_result r;
    if (fast_reference) {
      mm::plan_input fine = in;
      fine.config.resolution = mm::reference_grid(in.ego.limits, reference);
      fine.config.max_time_step = o.reference_time_step;
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
      if (!f.ok()) {
        std::fprintf(stderr, "scene %zu, fast %s: %s\n", s, setting.label().c_str(), f.error.c_str());
        return 1;
      }
      const double scene_worst = mm::plan_comparison::largest_index_difference(f, r).value;
      setting.errors.push_back(scene_worst);
      setting.worst = std::max(setting.worst, scene_worst);
      // Spec §11: the picks may differ where the fast one lies within 0.02 below the reference's in
      // the reference's own indices (one relevant obstacle: the map column decides the pick); with
      // several, τ̄ and the family where the reference's best forecast time leads by more.
      const bool disagrees =
          mm::plan_comparison::relevant_obstacles(r) == 1
              ? mm::plan_comparison::pick_shortfall(f, r) > accuracy_bound
              : mm::plan_comparison::forecast_time_margin(r) > accuracy_bound &&
                    (f.forecast_index != r.forecast_index || f.selected_family != r.selected_family);
      setting.disagreements += disagrees ? 1 : 0;
      if (signs) {
        mm::plan_input recorded = in;
        recorded.config.record_samples = true;
        const mm::plan_result fs = mm::plan(recorded);
        const mm::plan_result rs = mm::plan_reference(
            recorded, {setting.resolution, reference.proof_resolution, setting.resolution.accelerations});
        if (!fs.ok() || !rs.ok()) {
          std::fprintf(stderr, "scene %zu, signs at %s: %s\n", s, setting.label().c_str(), (fs.ok() ? rs : fs).error.c_str());
          return 1;
        }
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
  std::printf("reference %s %zux%zu (%zux1 without steering): %zu scenes (%zu interacting), %zu obstacle(s), "
              "%.1f ms per scene\n",
              fast_reference ? "(fast engine)" : "(reference engine)", reference.sampling.accelerations,
              reference.sampling.curvatures, reference.one_dimensional_accelerations, scenes,
              interacting, options.obstacles, 1e3 * reference_seconds / static_cast<double>(scenes));
  std::printf("%-16s %9s %9s %9s %10s %14s %12s\n", "fast", "max|dMI|", "p95", "median", "over 0.02", "disagreements",
              "ms/scene");
  for (fast_setting& setting : settings) {
    std::sort(setting.errors.begin(), setting.errors.end());
    const auto over = static_cast<std::size_t>(
        std::count_if(setting.errors.begin(), setting.errors.end(), [](double e) { return e > accuracy_bound; }));
    std::printf("%-16s %9.4f %9.4f %9.4f %10zu %14zu %12.3f\n", setting.label().c_str(), setting.worst,
                setting.errors[setting.errors.size() * 95 / 100], setting.errors[setting.errors.size() / 2], over,
                setting.disagreements, 1e3 * setting.seconds / static_cast<double>(scenes));
    if (signs) {
      std::printf("%-16s colliding (sample, tau) pairs for the reference at this grid: %zu; missed by the fast planner: %zu; "
                  "colliding for the fast planner only: %zu\n",
                  setting.label().c_str(), setting.colliding, setting.missed, setting.only_fast);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace cli = mm::tool_cli;
  accuracy_options o;
  CLI::App app{"Measures the fast planner against the reference planner (spec §11) on random scenes: the largest\n"
               "|MI_fast - MI_reference| over forecast times and families, and the disagreements of the pick (forecast\n"
               "time, family): with one relevant obstacle a fast pick more than 0.02 below the reference's in the\n"
               "reference's own indices; with several, a different forecast time or family where the reference's\n"
               "best forecast time leads by more than 0.02.\n",
               "maneuvermap_accuracy"};
  cli::add_whole(app, "--scenes", o.scenes, 1, cli::unbounded, "Random scenes to plan (>= 1)");
  cli::add_whole(app, "--seed", o.seed, 0, cli::unbounded, "Seed of the random scenes", "S");
  cli::add_whole(app, "--obstacles", o.scene.obstacles, 1, cli::unbounded, "Moving obstacles per scene (>= 1)", "K");
  cli::add_whole(app, "--noise", o.scene.sensor_noise, 0, 1, "1: Gaussian sensor noise on the obstacles' histories",
                 "0|1");
  app.add_option("--fast", o.fast,
                 "Fast settings to measure, comma-separated: A accelerations (2 to 2001) x C curvatures (1 to 2001) "
                 "per family @ time step DT [s] (> 0)")
      ->check(fast_settings())
      ->type_name("AxC@DT,...")
      ->capture_default_str();
  cli::add_whole(app, "--ref-accelerations", o.reference.sampling.accelerations, 2, mm::largest_sampling_side,
                 "Reference grid: accelerations per family (2 to 2001)", "A");
  cli::add_whole(app, "--ref-curvatures", o.reference.sampling.curvatures, 1, mm::largest_sampling_side,
                 "Reference grid: curvatures (1 to 2001)", "C");
  cli::add_whole(app, "--ref-accelerations-1d", o.reference.one_dimensional_accelerations, 2, mm::largest_sampling_side,
                 "Reference grid without steering: accelerations per family (2 to 2001)", "A");
  cli::add_real(app, "--ref-proof-resolution", o.reference.proof_resolution, cli::real_bound::positive, "s",
                "Time resolution of the reference's continuous-time collision proof [s] (> 0)", "S");
  app.add_option("--ref-engine", o.engine,
                 "reference: the reference planner; fast: the fast planner at the reference grid and "
                 "--ref-time-step (much cheaper, for convergence studies)")
      ->check(CLI::IsMember({"fast", "reference"}))
      ->type_name("ENGINE")
      ->capture_default_str();
  CLI::Option* time_step =
      cli::add_real(app, "--ref-time-step", o.reference_time_step, cli::real_bound::positive, "s",
                    "Time step of the fast engine as the reference [s] (> 0; with --ref-engine fast only)", "DT");
  cli::add_whole(app, "--signs", o.signs, 0, 1,
                 "1: also count, per fast setting, the (sample, forecast time) pairs that collide for the reference "
                 "at the same grid and those the fast planner misses",
                 "0|1");
  return cli::run(app, argc, argv, [&] {
    if (time_step->count() > 0 && o.engine != "fast") {
      throw CLI::ValidationError("--ref-time-step", "used only with --ref-engine fast");
    }
    return measure(o);
  });
}
