// Measures the fast forecast-time search (coordinate ascent) against the exhaustive one (spec §9)
// on random scenes with several obstacles: plans every scene with both searches and compares the
// room they leave, max(MI−, MI+) under the assignment each one selected.
//
//   maneuvermap_assignment [--scenes N] [--obstacles K] [--seed S] [--noise 0/1]
//
// Prints the share of scenes where the fast search is within 0.02 of the exhaustive optimum, the
// distribution of the shortfall, and the planning time with each search.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "mm/planner.hpp"
#include "random_scenes.hpp"

namespace {

double argument(int argc, char** argv, const char* name, double fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return std::atof(argv[i + 1]);
  }
  return fallback;
}

double room(const mm::plan_result& r) { return std::max(r.mi_brake_selected, r.mi_accelerate_selected); }

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  const auto scenes = static_cast<std::size_t>(argument(argc, argv, "--scenes", 1000));
  const auto obstacles = static_cast<std::size_t>(argument(argc, argv, "--obstacles", 2));
  const auto seed = static_cast<unsigned long long>(argument(argc, argv, "--seed", 9));
  const bool noise = argument(argc, argv, "--noise", 0) != 0.0;
  std::mt19937_64 rng(seed);
  std::vector<double> shortfall;  // exhaustive room − fast room, scenes with ≥ 2 relevant obstacles
  std::vector<double> fast_us;
  std::vector<double> exhaustive_us;
  std::size_t searched = 0;
  std::size_t within = 0;
  std::size_t better = 0;
  for (std::size_t s = 0; s < scenes; ++s) {
    mm::plan_input in = mm::testing::random_scene(rng, {obstacles, noise});
    in.config.assignment_search = mm::assignment_search_kind::coordinate_ascent;
    auto t0 = std::chrono::steady_clock::now();
    const mm::plan_result fast = mm::plan(in);
    auto t1 = std::chrono::steady_clock::now();
    in.config.assignment_search = mm::assignment_search_kind::exhaustive;
    const mm::plan_result exhaustive = mm::plan(in);
    auto t2 = std::chrono::steady_clock::now();
    if (!fast.ok() || !exhaustive.ok()) {
      std::fprintf(stderr, "scene %zu: %s%s\n", s, fast.error.c_str(), exhaustive.error.c_str());
      return 1;
    }
    std::size_t relevant = 0;
    for (const mm::obstacle_assessment& a : fast.obstacles) relevant += a.relevant ? 1 : 0;
    if (relevant < 2 || in.config.policy.kind != mm::forecast_policy_kind::adjustable) continue;
    ++searched;
    const double gap = room(exhaustive) - room(fast);
    shortfall.push_back(gap);
    within += gap <= 0.02 ? 1 : 0;
    better += gap < -1e-9 ? 1 : 0;
    fast_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    exhaustive_us.push_back(std::chrono::duration<double, std::micro>(t2 - t1).count());
  }
  std::printf("scenes %zu with %zu obstacles (seed %llu, noise %d); searched (>= 2 relevant obstacles): %zu\n", scenes,
              obstacles, seed, noise ? 1 : 0, searched);
  if (searched == 0) return 0;
  const double share = static_cast<double>(within) / static_cast<double>(searched);
  std::size_t exact = 0;
  for (const double g : shortfall) exact += std::abs(g) <= 1e-9 ? 1 : 0;
  std::printf("fast within 0.02 of the exhaustive optimum: %zu of %zu (%.1f %%); equal: %zu; fast better (ties broken differently): %zu\n",
              within, searched, 100.0 * share, exact, better);
  std::printf("shortfall exhaustive - fast: median %.4f  p95 %.4f  p99 %.4f  max %.4f\n", quantile(shortfall, 0.5),
              quantile(shortfall, 0.95), quantile(shortfall, 0.99), quantile(shortfall, 1.0));
  std::printf("plan time [us] with coordinate ascent: median %.0f  p99 %.0f; with exhaustive search: median %.0f  p99 %.0f\n",
              quantile(fast_us, 0.5), quantile(fast_us, 0.99), quantile(exhaustive_us, 0.5), quantile(exhaustive_us, 0.99));
  return share >= 0.95 ? 0 : 3;
}
