// The fast clearance computation against its brute-force reference (spec §11), on random scenes.
#include "mm/collision_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>

#include "mm/planner.hpp"
#include "property.hpp"
#include "random_scenes.hpp"

namespace mm {
namespace {

struct prepared {
  maneuver_samples samples;
  collision_window window;
  std::vector<forecast_obstacle> obstacles;
};

prepared prepare(const plan_input& in, double time_step) {
  prepared p;
  p.samples = sample_maneuvers(in.ego, in.nominal.curvature, in.config.displacement_horizon, in.config.resolution);
  p.window = {in.config.displacement_horizon, in.config.collision_window, time_step, in.config.safety_margin};
  for (const obstacle_track& track : in.obstacles) {
    p.obstacles.push_back({estimate_motion(track, in.config.history_window, in.time), track.shape});
  }
  return p;
}

/// Trial `trial` of the bit-for-bit tests: two obstacles, every other one turning, a margin in every
/// third, a coarse grid.
plan_input two_obstacle_scene(std::mt19937_64& rng, std::size_t trial) {
  plan_input in = testing::random_scene(rng, {2, trial % 2 == 1});
  in.config.safety_margin = trial % 3 == 0 ? 0.4 : 0.0;
  in.config.resolution = {7, 9};
  return in;
}

/// One obstacle of a bit-for-bit trial, with its brute-force clearances [forecast time][sample].
struct brute_force_case {
  const plan_input& in;
  const prepared& p;
  const ego_sweep& sweep;
  const forecast_obstacle& obstacle;
  const std::vector<clearance_set>& brute;
};

/// Calls `check` on every obstacle of the two-obstacle trials drawn from `seed`, until an assertion
/// fails.
template <class Check>
void for_each_brute_force_case(std::uint64_t seed, Check check) {
  std::mt19937_64 rng(seed);
  const std::size_t count = testing::property_count(12);
  const std::vector<double> taus = forecast_times(planner_config{});
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = two_obstacle_scene(rng, trial);
    const prepared p = prepare(in, 0.05);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    for (const forecast_obstacle& obstacle : p.obstacles) {
      const auto brute = clearances_reference(in.ego, p.samples, obstacle, taus, p.window);
      check(brute_force_case{in, p, sweep, obstacle, brute}, taus);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

TEST(collision_sets, fast_clearances_equal_the_clamped_brute_force_ones_bit_for_bit) {
  constexpr double cap = 2.0;
  for_each_brute_force_case(testing::property_seed(), [&](const brute_force_case& c, const std::vector<double>& taus) {
    const auto fast = clearances(c.sweep, c.obstacle, taus, cap);
    ASSERT_EQ(fast.size(), c.brute.size());
    for (std::size_t i = 0; i < taus.size(); ++i) {
      for (std::size_t m = 0; m < c.p.samples.size(); ++m) {
        ASSERT_EQ(fast[i][m], std::clamp(c.brute[i][m], -cap, cap))
            << "tau " << taus[i] << " sample " << m << "\n" << testing::describe(c.in);
      }
    }
  });
}

TEST(collision_sets, the_raster_finds_exactly_the_samples_that_overlap_at_a_sample_time_on_the_straight_part_or_between) {
  // Straight after construction, before any value is asked for: the collisions are those of a test
  // of every sample at every sample time before the straight part, of the closed form on it, and of
  // the refined minimum of the samples that came within their θ at a sample time (a contact between
  // sample times); the entries made exact on the way (where no direction separated a sample from
  // the obstacle over a pair of sample times) are exact, the others' −cap for a collision and +cap
  // elsewhere.
  constexpr double cap = 2.0;
  std::size_t colliding = 0;
  std::size_t between_samples = 0;
  std::size_t found_between = 0;
  for_each_brute_force_case(testing::property_seed() + 3, [&](const brute_force_case& c, const std::vector<double>& taus) {
    const clearance_field field(c.sweep, c.obstacle, taus, cap);
    const auto sampled = collisions_reference(c.in.ego, c.p.samples, c.obstacle, taus, c.p.window);
    for (std::size_t i = 0; i < taus.size(); ++i) {
      for (std::size_t m = 0; m < c.p.samples.size(); ++m) {
        const bool expected = sampled[i].test(m);
        ASSERT_EQ(field.collisions(i).test(m), expected)
            << "tau " << taus[i] << " sample " << m << " brute force " << c.brute[i][m] << "\n"
            << testing::describe(c.in);
        if (field.is_exact(i, m)) {
          ASSERT_EQ(field.set(i)[m] <= 0.0, expected) << "tau " << taus[i] << " sample " << m;
          found_between += expected ? 1 : 0;
        } else {
          ASSERT_EQ(field.set(i)[m], expected ? -cap : cap) << "tau " << taus[i] << " sample " << m;
        }
        // A collision is a clearance ≤ 0; the converse fails only between sample times.
        if (expected) {
          ASSERT_LE(c.brute[i][m], 0.0);
        }
        colliding += expected ? 1 : 0;
        between_samples += !expected && c.brute[i][m] <= 0.0 ? 1 : 0;
      }
      ASSERT_EQ(field.collides(i), !sampled[i].none());
    }
  });
  EXPECT_GT(colliding, 0u);
  std::printf("collisions: %zu, of which touch only between sample times (found by their exact clearance): %zu; "
              "such contacts not found: %zu\n",
              colliding, found_between, between_samples);
}

TEST(collision_sets, a_small_fast_obstacle_turning_hard_gets_the_reference_s_collisions) {
  // A disc of 5 cm at 24–26 m/s turning at 1.5–2 rad/s (A_o = v·ω of 36–53 m/s²) past an ego at
  // 12 m/s: the field's waits and proofs between sample times must bound how far its curve bends
  // from a straight line (the A_o term). Without it the field missed a collision of sample 46
  // (first scene) and of sample 90 (second) under several forecast times, 12 entries in all (found
  // by a search of 6,000 random such scenes with the term removed, 2026-12-07: these 12 of the
  // reference's 610,988 collisions; no other test failed without it).
  struct scene {
    double ego_speed, speed, yaw_rate;
    vec2 at;
    double heading;
  };
  const std::array<scene, 2> scenes{{
      {12.620188255292113, 23.952544400943282, -1.5218687406275551, {-13.511752788557459, -0.024320092012739991},
       0.93576386009413726},
      {11.719101251806631, 26.418706065255911, -1.9875994122322307, {-10.954894820264165, 5.9276748700491098},
       0.73056357487032386},
  }};
  const std::vector<double> taus = forecast_times(planner_config{});
  for (const scene& sc : scenes) {
    ego_state ego;
    ego.pose = {{0.0, 0.0}, 0.0};
    ego.speed = sc.ego_speed;
    const maneuver_samples samples = sample_maneuvers(ego, 0.0, 1.0, {7, 9});
    const collision_window window{1.0, 3.0, 0.05, 0.0};
    const forecast_obstacle obstacle{{{sc.at, sc.heading}, sc.speed, sc.yaw_rate}, disc{0.05}};
    const ego_sweep sweep(ego, samples, window);
    const clearance_field field(sweep, obstacle, taus, 2.0);
    const auto reference = collisions_reference(ego, samples, obstacle, taus, window);
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < taus.size(); ++i) {
      for (std::size_t m = 0; m < samples.size(); ++m) {
        EXPECT_EQ(field.collisions(i).test(m), reference[i].test(m))
            << "obstacle at " << sc.speed << " m/s, " << sc.yaw_rate << " rad/s: tau " << taus[i] << ", sample " << m;
        colliding += reference[i].test(m) ? 1 : 0;
      }
    }
    EXPECT_GT(colliding, 0U);
  }
}

TEST(collision_sets, contacts_between_sample_times_are_found_as_the_reference_finds_them_at_a_coarse_time_step) {
  // At a step of 0.2 s many samples touch an obstacle only between sample times: those within θ at
  // a sample time are looked at, pair of sample times by pair, and only where no direction separates
  // them over the pair (`separated_throughout`) is their exact clearance asked for. The collisions
  // must still be the reference's, sample for sample.
  constexpr double cap = 2.0;
  std::mt19937_64 rng(testing::property_seed() + 43);
  const std::size_t count = testing::property_count(40);
  const std::vector<double> taus = forecast_times(planner_config{});
  std::size_t between = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    const plan_input in = two_obstacle_scene(rng, trial);
    const prepared p = prepare(in, 0.2);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    const std::vector<double> times = sample_times(p.window.duration, p.window.time_step);
    for (const forecast_obstacle& obstacle : p.obstacles) {
      const clearance_field field(sweep, obstacle, taus, cap);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        // `collisions_reference`'s set is the samples with a first overlap.
        const auto first = first_overlaps_reference(in.ego, p.samples, obstacle, taus[i], p.window);
        for (std::size_t m = 0; m < p.samples.size(); ++m) {
          const bool collides = first[m] != no_collision;
          ASSERT_EQ(field.collisions(i).test(m), collides)
              << "trial " << trial << " tau " << taus[i] << " sample " << m << "\n" << testing::describe(in);
          // A contact found between sample times is put at the sampled minimum's time, where the
          // sample does not overlap.
          if (collides && first[m] < straight_part_start(obstacle, taus[i], p.window)) {
            const auto at = std::find(times.begin(), times.end(), first[m]);
            ASSERT_NE(at, times.end());
            const maneuver& u = p.samples.maneuvers[m];
            between += clearance_at(in.ego, u, obstacle, taus[i], first[m], p.window) > 0.0 ? 1 : 0;
          }
        }
      }
    }
  }
  std::printf("contacts between sample times: %zu\n", between);
  EXPECT_GT(between, count);
}

TEST(collision_sets, every_pair_of_shapes_gets_the_collisions_and_clearances_of_its_reference) {
  // The raster's closed forms differ by shape pair: two rectangles, a rectangle and a disc, any
  // other pair (a polygon obstacle, or a disc-shaped ego). Each obstacle of the two-obstacle scenes
  // is made a disc (up to 2 m: where a block is decided by its centre's face separation, a disc
  // centre outside the rectangle must not count as inside), a hexagon or kept a rectangle in turn,
  // and the ego a disc in every fourth trial; the clearances are compared in every fifth trial.
  constexpr double cap = 2.0;
  std::mt19937_64 rng(testing::property_seed() + 37);
  std::uniform_real_distribution<double> radius(0.3, 2.0);
  const std::vector<double> taus = forecast_times(planner_config{});
  std::size_t colliding = 0;
  for (std::size_t trial = 0; trial < testing::property_count(120); ++trial) {
    plan_input in = two_obstacle_scene(rng, trial);
    if (trial % 4 == 3) in.ego.shape = disc{1.2};
    for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
      switch ((trial + j) % 3) {
        case 0:
          in.obstacles[j].shape = disc{radius(rng)};
          break;
        case 1:
          in.obstacles[j].shape = convex_polygon{{{1.5, 0.0}, {0.8, 0.9}, {-0.8, 0.9}, {-1.5, 0.0}, {-0.8, -0.9}, {0.8, -0.9}}};
          break;
        default:
          break;
      }
    }
    const prepared p = prepare(in, 0.05);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    for (const forecast_obstacle& obstacle : p.obstacles) {
      const auto expected = collisions_reference(in.ego, p.samples, obstacle, taus, p.window);
      const clearance_field field(sweep, obstacle, taus, cap);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        ASSERT_EQ(field.collisions(i), expected[i]) << "trial " << trial << " tau " << taus[i] << "\n" << testing::describe(in);
        colliding += expected[i].count();
      }
      if (trial % 5 != 0) continue;
      const auto brute = clearances_reference(in.ego, p.samples, obstacle, taus, p.window);
      const auto fast = clearances(sweep, obstacle, taus, cap);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        for (std::size_t m = 0; m < p.samples.size(); ++m) {
          ASSERT_EQ(fast[i][m], std::clamp(brute[i][m], -cap, cap))
              << "trial " << trial << " tau " << taus[i] << " sample " << m << "\n" << testing::describe(in);
        }
      }
    }
  }
  EXPECT_GT(colliding, 0u);
}

TEST(collision_sets, neighbours_found_inert_from_their_forecast_placements_alone_have_the_reference_s_clearances) {
  // The scenes' obstacles moved in a random direction, the first 0 to 15 m, the second 40 to 80 m:
  // near ones are rastered, far ones are shown inert from their placements at the forecast times
  // (`far_at_every_time`; the counts are printed, those the raster alone finds inert too). Every
  // field has the clamped brute-force clearances bit for bit and the reference's collisions, and is
  // inert whether or not it records its first overlaps (which rasters every field).
  constexpr double cap = 2.0;
  std::mt19937_64 rng(testing::property_seed() + 41);
  std::uniform_real_distribution<double> near(0.0, 15.0);
  std::uniform_real_distribution<double> far(40.0, 80.0);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  const std::vector<double> taus = forecast_times(planner_config{});
  std::size_t up_front = 0;
  std::size_t by_raster = 0;
  std::size_t not_inert = 0;
  for (std::size_t trial = 0; trial < testing::property_count(16); ++trial) {
    plan_input in = two_obstacle_scene(rng, trial);
    for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
      obstacle_track& track = in.obstacles[j];
      const vec2 offset = (j == 0 ? near(rng) : far(rng)) * unit_vector(angle(rng));
      for (observation& o : track.history) o.pose.position = o.pose.position + offset;
    }
    const prepared p = prepare(in, 0.05);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    clearance_field::raster_scratch scratch;
    for (const forecast_obstacle& obstacle : p.obstacles) {
      const clearance_field field(sweep, obstacle, taus, cap);
      const clearance_field recorded(sweep, obstacle, taus, cap, {}, scratch, clearance_field::recording::first_overlaps);
      ASSERT_EQ(field.inert(), recorded.inert()) << "trial " << trial << "\n" << testing::describe(in);
      const auto sampled = collisions_reference(in.ego, p.samples, obstacle, taus, p.window);
      const auto brute = clearances_reference(in.ego, p.samples, obstacle, taus, p.window);
      const auto fast = clearances(sweep, obstacle, taus, cap);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        ASSERT_EQ(field.collisions(i), sampled[i]) << "trial " << trial << " tau " << taus[i] << "\n" << testing::describe(in);
        for (std::size_t m = 0; m < p.samples.size(); ++m) {
          ASSERT_EQ(fast[i][m], std::clamp(brute[i][m], -cap, cap))
              << "trial " << trial << " tau " << taus[i] << " sample " << m << "\n" << testing::describe(in);
        }
      }
      if (!field.inert()) {
        ++not_inert;
      } else if (field.statistics().placements == taus.size()) {
        ++up_front;
      } else {
        ++by_raster;
      }
    }
  }
  std::printf("fields inert from their forecast placements: %zu, inert found by the raster: %zu, not inert: %zu\n",
              up_front, by_raster, not_inert);
  EXPECT_GT(up_front, 0u);
  EXPECT_GT(not_inert, 0u);
}

TEST(collision_sets, a_field_rastered_in_reused_scratch_equals_a_fresh_one_bit_for_bit) {
  // One scratch for every field of every trial, whose sweeps differ in size (the grid alternates),
  // and whose wanted forecast times vary: nothing of an earlier field may leak into a later one.
  constexpr double cap = 2.0;
  std::mt19937_64 rng(testing::property_seed() + 23);
  const std::vector<double> taus = forecast_times(planner_config{});
  const std::array<sampling_resolution, 3> grids{{{7, 9}, {5, 5}, {9, 13}}};
  clearance_field::raster_scratch scratch;
  std::size_t colliding = 0;
  for (std::size_t trial = 0; trial < testing::property_count(12); ++trial) {
    plan_input in = two_obstacle_scene(rng, trial);
    in.config.resolution = grids[trial % grids.size()];
    const prepared p = prepare(in, 0.05);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    std::vector<std::uint8_t> wanted(taus.size(), 1);
    if (trial % 2 == 1) {
      for (std::size_t i = 0; i < wanted.size(); ++i) wanted[i] = (i + trial) % 3 == 0 ? 1 : 0;
    }
    for (const forecast_obstacle& obstacle : p.obstacles) {
      clearance_field reused(sweep, obstacle, taus, cap, wanted, scratch);
      clearance_field fresh(sweep, obstacle, taus, cap, wanted);
      ASSERT_EQ(reused.inert(), fresh.inert()) << testing::describe(in);
      for (std::size_t i = 0; i < taus.size(); ++i) {
        if (!fresh.evaluated(i)) continue;
        ASSERT_EQ(reused.collisions(i), fresh.collisions(i))
            << "trial " << trial << " tau " << taus[i] << "\n" << testing::describe(in);
        colliding += fresh.collisions(i).count();
        for (std::size_t m = 0; m < p.samples.size(); ++m) {
          ASSERT_EQ(reused.exact(i, m), fresh.exact(i, m)) << "trial " << trial << " tau " << taus[i] << " sample " << m;
        }
      }
    }
  }
  EXPECT_GT(colliding, 0u);
}

TEST(collision_sets, recorded_first_overlaps_are_the_first_times_at_which_each_sample_overlaps) {
  // One forecast time at a time (as the near-crash choice asks) and all at once, in one scratch.
  constexpr double cap = 2.0;
  std::size_t overlapping = 0;
  clearance_field::raster_scratch scratch;
  for_each_brute_force_case(testing::property_seed() + 29, [&](const brute_force_case& c, const std::vector<double>& taus) {
    const clearance_field all(c.sweep, c.obstacle, taus, cap, {}, scratch, clearance_field::recording::first_overlaps);
    for (std::size_t i = 0; i < taus.size(); i += 3) {
      std::vector<std::uint8_t> only(taus.size(), 0);
      only[i] = 1;
      const clearance_field one(c.sweep, c.obstacle, taus, cap, only, scratch, clearance_field::recording::first_overlaps);
      const std::vector<double> expected = first_overlaps_reference(c.in.ego, c.p.samples, c.obstacle, taus[i], c.p.window);
      for (std::size_t m = 0; m < c.p.samples.size(); ++m) {
        ASSERT_EQ(one.first_overlap(i, m), expected[m]) << "tau " << taus[i] << " sample " << m << "\n" << testing::describe(c.in);
        ASSERT_EQ(all.first_overlap(i, m), expected[m]) << "tau " << taus[i] << " sample " << m;
        ASSERT_EQ(one.collisions(i).test(m), expected[m] != no_collision);
        overlapping += expected[m] != no_collision ? 1 : 0;
      }
      if (i + 1 < taus.size() && !one.forecast_independent()) {
        EXPECT_THROW((void)one.first_overlap(i + 1, 0), std::logic_error);  // its set was not computed
      }
    }
  });
  EXPECT_GT(overlapping, 0u);
}

TEST(collision_sets, a_field_without_recording_refuses_to_give_first_overlaps) {
  std::mt19937_64 rng(testing::property_seed() + 31);
  const plan_input in = two_obstacle_scene(rng, 1);
  const prepared p = prepare(in, 0.05);
  const ego_sweep sweep(in.ego, p.samples, p.window);
  const clearance_field field(sweep, p.obstacles.front(), forecast_times(planner_config{}), 2.0);
  EXPECT_THROW((void)field.first_overlap(0, 0), std::logic_error);
}

TEST(collision_sets, clearance_is_negative_for_every_sampled_collision_and_finds_most_contacts_between_samples) {
  std::mt19937_64 rng(testing::property_seed() + 17);
  const std::size_t count = testing::property_count(12);
  const std::vector<double> taus = forecast_times(planner_config{});
  std::size_t colliding = 0;
  std::size_t fine_only = 0;
  std::size_t fine_only_found = 0;
  for (std::size_t trial = 0; trial < count; ++trial) {
    plan_input in = testing::random_scene(rng, {1, false});
    in.config.safety_margin = trial % 2 == 0 ? 0.5 : 0.0;
    in.config.resolution = {7, 9};
    const prepared p = prepare(in, 0.05);
    const ego_sweep sweep(in.ego, p.samples, p.window);
    const auto fast = clearances(sweep, p.obstacles[0], taus, 2.0);
    collision_window fine_window = p.window;
    fine_window.time_step = 0.005;
    const auto collides = [&](std::size_t m, double tau, const collision_window& window) {
      return maneuver_collides(in.ego, p.samples.maneuvers[m], std::span(&p.obstacles[0], 1), std::vector<double>{tau}, window);
    };
    for (std::size_t i = 0; i < taus.size(); ++i) {
      for (std::size_t m = 0; m < p.samples.size(); ++m) {
        if (collides(m, taus[i], p.window)) {
          ASSERT_LT(fast[i][m], 0.0) << "tau " << taus[i] << " sample " << m << "\n" << testing::describe(in);
          ++colliding;
        } else if (collides(m, taus[i], fine_window)) {
          ++fine_only;
          fine_only_found += fast[i][m] < 0.0 ? 1 : 0;
        }
      }
    }
  }
  EXPECT_GT(colliding, 0u) << "the random scenes must produce collisions for this test to mean anything";
  // Contacts only a 10× finer step sees: the refined minimum recognises most of them.
  std::printf("contacts between samples: %zu, recognised by the refined clearance: %zu\n", fine_only, fine_only_found);
  EXPECT_GE(static_cast<double>(fine_only_found), 0.9 * static_cast<double>(fine_only));
}

TEST(collision_sets, clearance_of_a_forecast_time_covers_the_shared_turning_part) {
  // With τ ≥ T_c the whole forecast turns; with τ = 0 it never does; clearances differ.
  plan_input in;
  in.ego.speed = 10.0;
  obstacle_track b;
  b.history = testing::ctrv_history({{20.0, 12.0}, -1.5707963}, 8.0, -0.8, 0.0);
  in.obstacles.push_back(b);
  in.config.resolution = {5, 5};
  const prepared p = prepare(in, 0.02);
  const ego_sweep sweep(in.ego, p.samples, p.window);
  const std::vector<double> taus{0.0, 1.0, 2.0, 3.0};
  const auto c = clearances(sweep, p.obstacles[0], taus, 2.0);
  const std::size_t straight_on = p.samples.grid(family::accelerate).begin + 2;  // a = 0, κ = 0
  EXPECT_LT(c[0][straight_on], 0.0) << "straight-line forecast: B crosses the ego's lane";
  EXPECT_GT(c[3][straight_on], 0.0) << "turning forecast: B turns away before the lane";
}

TEST(collision_sets, a_restarted_sweep_is_a_new_sweep_bit_for_bit) {
  // Two planning steps of one vehicle: a new pose, nominal curvature and window, and in two trials of
  // three a new speed, at which the samples are sampled again (the tree of blocks is kept). The
  // first five trials (the sanitizer build's count) cover each kind of trial.
  std::mt19937_64 rng(testing::property_seed() + 11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t restarted_at_a_new_speed = 0;
  std::size_t restarted_with_moved_rows = 0;
  for (std::size_t trial = 0; trial < testing::property_count(20); ++trial) {
    plan_input first = testing::random_scene(rng, {1, false});
    plan_input second = testing::random_scene(rng, {1, false});
    const bool new_speed = trial % 3 != 0;
    if (!new_speed) second.ego.speed = first.ego.speed;
    if (trial % 3 == 1) {
      // Both below d_max·T_h: the braking rows are evenly spaced in the arc length, and move.
      first.ego.speed = 1.0 + 5.0 * unit(rng);
      second.ego.speed = 1.0 + 5.0 * unit(rng);
    } else if (trial % 6 == 2) {
      // Both above it: the rows are evenly spaced in a at either speed, the same rows.
      first.ego.speed = 7.5 + 12.0 * unit(rng);
      second.ego.speed = 7.5 + 12.0 * unit(rng);
    }
    second.ego.limits = first.ego.limits;
    second.ego.shape = first.ego.shape;
    second.nominal.curvature = (2.0 * unit(rng) - 1.0) * max_curvature(first.ego.speed, first.ego.limits);
    SCOPED_TRACE(testing::describe(second));
    maneuver_samples samples = prepare(first, 0.05).samples;
    ego_sweep restarted(first.ego, samples, {1.0, 3.0, 0.05, 0.0});
    // Every placement and straight part cached, the nominal-curvature columns' included (which the
    // restart rewrites).
    for (std::size_t k = 0; k < restarted.times().size(); ++k) {
      for (std::size_t m = 0; m < samples.size(); ++m) restarted.at(k, m);
    }
    for (std::size_t m = 0; m < samples.size(); ++m) restarted.straight_line(m);
    if (new_speed) {
      samples = prepare(second, 0.05).samples;
    } else {
      set_nominal_curvature(samples, second.ego, second.nominal.curvature, second.config.displacement_horizon);
    }
    // Every other trial the same sample times (the placements in the ego's frame are kept), the
    // others a new time step and duration.
    const collision_window window = trial % 2 == 0 ? collision_window{1.0, 3.0, 0.05, 0.3 * unit(rng)}
                                                   : collision_window{1.0, 2.5, 0.02 + 0.03 * unit(rng), 0.3 * unit(rng)};
    // A slow ego's rows follow the arc length (`available_displacements`): at a new speed they move,
    // and the tree is kept all the same.
    const bool rows_moved = samples.brake.samples[samples.brake.curvature_count].u.acceleration !=
                            prepare(first, 0.05).samples.brake.samples[samples.brake.curvature_count].u.acceleration;
    ASSERT_TRUE(restarted.try_restart(second.ego, window));
    restarted_at_a_new_speed += new_speed ? 1 : 0;
    restarted_with_moved_rows += rows_moved ? 1 : 0;
    const maneuver_samples fresh_samples = prepare(second, 0.05).samples;
    ASSERT_EQ(samples.maneuvers, fresh_samples.maneuvers);
    ASSERT_EQ(samples.area_weights, fresh_samples.area_weights);
    ASSERT_EQ(samples.end_points, fresh_samples.end_points);
    const ego_sweep fresh(second.ego, fresh_samples, window);
    ASSERT_EQ(restarted.times(), fresh.times());
    ASSERT_EQ(restarted.order(), fresh.order());
    ASSERT_EQ(restarted.roots(), fresh.roots());
    ASSERT_EQ(restarted.blocks().size(), fresh.blocks().size());
    for (std::size_t b = 0; b < fresh.blocks().size(); ++b) {
      const ego_sweep::block& x = restarted.blocks()[b];
      const ego_sweep::block& y = fresh.blocks()[b];
      ASSERT_TRUE(x.begin == y.begin && x.end == y.end && x.centre == y.centre && x.second == y.second &&
                  x.acceleration_spread == y.acceleration_spread && x.curvature_spread == y.curvature_spread &&
                  x.top_acceleration == y.top_acceleration && x.largest_deceleration == y.largest_deceleration &&
                  x.largest_curvature == y.largest_curvature)
          << "block " << b;
      for (std::size_t k = 0; k < fresh.times().size(); k += 5) {
        ASSERT_EQ(restarted.block_spread(x, k), fresh.block_spread(y, k)) << "block " << b << " time " << k;
      }
    }
    ASSERT_EQ(restarted.largest_point_speed(), fresh.largest_point_speed());
    for (std::size_t k = 0; k < fresh.times().size(); ++k) {
      ASSERT_EQ(restarted.reach_radius(k), fresh.reach_radius(k));
      for (std::size_t m = 0; m < fresh_samples.size(); ++m) {
        const placement a = restarted.at(k, m);
        const placement b = fresh.at(k, m);
        ASSERT_TRUE(a.position == b.position && a.direction == b.direction) << "time " << k << " sample " << m;
        ASSERT_EQ(restarted.sample_speed(m), fresh.sample_speed(m)) << "sample " << m;
        const ego_sweep::line x = restarted.straight_line(m);
        const ego_sweep::line y = fresh.straight_line(m);
        ASSERT_TRUE(x.start == y.start && x.velocity == y.velocity && restarted.straight_direction(m) == fresh.straight_direction(m))
            << "straight part of sample " << m;
        ASSERT_EQ(restarted.sample_point_speed(m), fresh.sample_point_speed(m)) << "sample " << m;
      }
    }
  }
  EXPECT_GT(restarted_at_a_new_speed, 0u) << "some trials must restart at a new speed";
  EXPECT_GT(restarted_with_moved_rows, 0u) << "some trials must restart where the rows moved";
}

TEST(collision_sets, a_sweep_restarted_twice_unlooked_at_takes_the_extents_its_rows_moved_anew) {
  // Slow, then fast, then fast again: the second restart's rows are the first's, but the blocks not
  // looked at since the first restart must still take their acceleration extents anew.
  std::mt19937_64 rng(testing::property_seed() + 14);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t trial = 0; trial < testing::property_count(5); ++trial) {
    plan_input in = testing::random_scene(rng, {1, false});
    const auto at_speed = [&](double v) {
      plan_input out = in;
      out.ego.speed = v;
      return out;
    };
    const plan_input slow = at_speed(1.0 + 5.0 * unit(rng));
    // Below the cap of 30 m/s by more than a_max·T_h: the rows of either family are evenly spaced in a.
    const plan_input fast = at_speed(8.0 + 5.0 * unit(rng));
    const plan_input faster = at_speed(13.5 + 5.0 * unit(rng));
    ASSERT_LT(faster.ego.speed + faster.ego.limits.max_acceleration * faster.config.displacement_horizon,
              faster.ego.limits.speed_cap);
    SCOPED_TRACE(testing::describe(slow));
    const collision_window window{1.0, 3.0, 0.05, 0.0};
    maneuver_samples samples = prepare(slow, 0.05).samples;
    ego_sweep restarted(slow.ego, samples, window);
    (void)restarted.blocks();
    samples = prepare(fast, 0.05).samples;
    ASSERT_TRUE(restarted.try_restart(fast.ego, window));
    samples = prepare(faster, 0.05).samples;
    ASSERT_TRUE(restarted.try_restart(faster.ego, window));
    const maneuver_samples fresh_samples = prepare(faster, 0.05).samples;
    const ego_sweep fresh(faster.ego, fresh_samples, window);
    ASSERT_EQ(restarted.blocks().size(), fresh.blocks().size());
    for (std::size_t b = 0; b < fresh.blocks().size(); ++b) {
      const ego_sweep::block& x = restarted.blocks()[b];
      const ego_sweep::block& y = fresh.blocks()[b];
      ASSERT_TRUE(x.acceleration_spread == y.acceleration_spread && x.top_acceleration == y.top_acceleration &&
                  x.largest_deceleration == y.largest_deceleration && x.curvature_spread == y.curvature_spread &&
                  x.largest_curvature == y.largest_curvature)
          << "block " << b << ": acceleration spread " << x.acceleration_spread << " against " << y.acceleration_spread;
    }
  }
}

TEST(collision_sets, a_sweep_restarted_hundreds_of_times_places_as_a_new_one) {
  // The placement cache is invalidated by a stamp per start with other sample times, which wraps
  // after 255 such starts. A sweep places sample 0 at its first start, is restarted n times at
  // other poses and alternately shorter windows (as many sample times, the last one earlier)
  // without being asked for samples 0 and 1, and must then place both as a new sweep does — for
  // every n around the wrap.
  std::mt19937_64 rng(testing::property_seed() + 13);
  const plan_input in = testing::random_scene(rng, {1, false});
  const maneuver_samples samples = prepare(in, 0.05).samples;
  const collision_window window{1.0, 3.0, 0.05, 0.0};
  const collision_window shorter{1.0, 2.99, 0.05, 0.0};
  ASSERT_EQ(sample_times(2.99, 0.05).size(), sample_times(3.0, 0.05).size());
  const auto window_of = [&](int start) { return start % 2 == 0 ? window : shorter; };
  const auto pose_of = [&](int start) {
    ego_state ego = in.ego;
    ego.pose.position.x += 0.25 * static_cast<double>(start);
    ego.pose.heading += 0.001 * static_cast<double>(start);
    return ego;
  };
  for (int n = 250; n <= 262; ++n) {
    ego_sweep restarted(pose_of(0), samples, window_of(0));
    for (std::size_t k = 0; k < restarted.times().size(); ++k) restarted.at(k, 0);
    for (int start = 1; start <= n; ++start) {
      restarted.restart(pose_of(start), window_of(start));
      restarted.at(static_cast<std::size_t>(start) % restarted.times().size(), 2);
    }
    const ego_sweep fresh(pose_of(n), samples, window_of(n));
    for (const std::size_t m : {0U, 1U}) {
      for (std::size_t k = 0; k < fresh.times().size(); ++k) {
        const placement a = restarted.at(k, m);
        const placement b = fresh.at(k, m);
        ASSERT_TRUE(a.position == b.position && a.direction == b.direction)
            << "after " << n << " restarts, time " << k << " sample " << m;
      }
    }
  }
}

TEST(collision_sets, a_sweep_refuses_to_restart_with_other_limits_or_a_grid_of_another_shape) {
  std::mt19937_64 rng(testing::property_seed() + 12);
  plan_input in = testing::random_scene(rng, {1, false});
  maneuver_samples samples = prepare(in, 0.05).samples;
  ego_sweep sweep(in.ego, samples, {1.0, 3.0, 0.05, 0.0});
  plan_input other = in;
  other.ego.limits.max_acceleration += 0.5;
  EXPECT_FALSE(sweep.try_restart(other.ego, {1.0, 3.0, 0.05, 0.0}));
  EXPECT_THROW(sweep.restart(other.ego, {1.0, 3.0, 0.05, 0.0}), std::invalid_argument);
  // At a new speed the samples must have been sampled again with the same grid.
  other = in;
  other.ego.speed += 0.5;
  other.config.resolution = {in.config.resolution.accelerations, in.config.resolution.curvatures + 2};
  samples = prepare(other, 0.05).samples;
  EXPECT_FALSE(sweep.try_restart(other.ego, {1.0, 3.0, 0.05, 0.0}));
  EXPECT_THROW(sweep.restart(other.ego, {1.0, 3.0, 0.05, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace mm
