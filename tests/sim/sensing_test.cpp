#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "mm/sim/simulation.hpp"
#include "sensing.hpp"
#include "sim/scenarios.hpp"

namespace {

using namespace mm::sim;
using mm::sim::testing::crossing;
using mm::sim::testing::cruising;
using mm::sim::testing::straight_path;
constexpr double pi = std::numbers::pi;

/// A stands still at the origin, not planning; B circles it at 15 m and 5 m/s.
scenario watcher(sensing_noise noise, std::uint64_t seed) {
  scenario s;
  s.duration = 10.0;
  s.seed = seed;
  s.noise = noise;
  planning_vehicle a = cruising("A", straight_path({-10.0, 0.0}, 0.0, 100.0), 0.0);
  a.start_arc_length = 10.0;
  a.avoidance = false;
  s.planning_vehicles.push_back(a);
  s.scripted_vehicles.push_back(mm::sim::testing::scripted("B", path::circular_arc({0.0, 0.0}, 15.0, 0.0, 20.0 * pi), 5.0));
  return s;
}

struct moments {
  double mean = 0.0;
  double sd = 0.0;
};

moments moments_of(const std::vector<double>& x) {
  moments m;
  for (const double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (const double v : x) m.sd += (v - m.mean) * (v - m.mean);
  m.sd = std::sqrt(m.sd / static_cast<double>(x.size() - 1));
  return m;
}

TEST(sim_sensing, observation_noise_is_gaussian_with_the_requested_standard_deviations) {
  const sensing_noise noise{0.2, 0.05, 0.3};
  simulation sim(watcher(noise, 7));
  std::vector<double> dx, dy, dh, dv;
  run(sim, [&](const simulation& now) {
    const std::optional<mm::plan_input> input = now.planning_input(0);
    if (input->obstacles.empty() || now.ended()) return;  // nothing is sensed once the run has ended
    const mm::observation& seen = input->obstacles[0].history.back();
    const agent_state& truth = now.state(1);
    EXPECT_DOUBLE_EQ(seen.time, now.time());
    dx.push_back(seen.pose.position.x - truth.pose.position.x);
    dy.push_back(seen.pose.position.y - truth.pose.position.y);
    dh.push_back(mm::wrap_angle(seen.pose.heading - truth.pose.heading));
    dv.push_back(seen.speed - truth.speed);
  });
  ASSERT_EQ(dx.size(), 999U);  // steps 1..999: a track needs two observations
  const double n = static_cast<double>(dx.size());
  const moments mx = moments_of(dx), my = moments_of(dy), mh = moments_of(dh), mv = moments_of(dv);
  std::printf("noise sd: x %.4f y %.4f heading %.4f speed %.4f; means %.4f %.4f %.4f %.4f\n", mx.sd, my.sd, mh.sd,
              mv.sd, mx.mean, my.mean, mh.mean, mv.mean);
  // Means within 4 standard errors of 0; standard deviations within 4 standard errors (σ/√(2n)).
  const auto check = [&](const moments& m, double sigma) {
    EXPECT_LT(std::abs(m.mean), 4.0 * sigma / std::sqrt(n));
    EXPECT_LT(std::abs(m.sd - sigma), 4.0 * sigma / std::sqrt(2.0 * n));
  };
  check(mx, 0.2);
  check(my, 0.2);
  check(mh, 0.05);
  check(mv, 0.3);
  double cross = 0.0;
  for (std::size_t i = 0; i < dx.size(); ++i) cross += (dx[i] - mx.mean) * (dy[i] - my.mean);
  EXPECT_LT(std::abs(cross / (n * mx.sd * my.sd)), 4.0 / std::sqrt(n));  // x and y independent
  double lag = 0.0;
  for (std::size_t i = 1; i < dx.size(); ++i) lag += (dx[i] - mx.mean) * (dx[i - 1] - mx.mean);
  EXPECT_LT(std::abs(lag / (n * mx.sd * mx.sd)), 4.0 / std::sqrt(n));  // white in time
}

TEST(sim_sensing, the_ring_keeps_its_largest_speed_as_a_scan_finds_it) {
  // Rings of several capacities fed runs of rising, falling, equal and negative (noisy) speeds;
  // after every push the O(1) maximum equals the scan's, bit for bit, and the entries are in order.
  std::mt19937_64 random(20261202);
  for (const std::size_t capacity : {1U, 2U, 3U, 7U, 52U}) {
    mm::sim::detail::observation_ring ring(capacity);
    double speed = 5.0;
    for (int push = 0; push < 2000; ++push) {
      const int kind = static_cast<int>(random() % 4);
      if (kind == 0) speed += 0.25;
      if (kind == 1) speed -= 0.5;
      if (kind == 3) speed = std::uniform_real_distribution<double>(-0.2, 9.0)(random);
      mm::observation o;
      o.time = 0.01 * push;
      o.speed = speed;
      ring.push(o);
      ASSERT_EQ(ring.max_speed(), ring.max_speed_by_scan()) << "capacity " << capacity << " push " << push;
      std::vector<mm::observation> copy;
      ring.copy_to(copy);
      ASSERT_EQ(copy.size(), std::min<std::size_t>(capacity, push + 1));
      EXPECT_EQ(copy.back().time, o.time);
      for (std::size_t i = 1; i < copy.size(); ++i) ASSERT_LT(copy[i - 1].time, copy[i].time);
    }
    ring.clear();
    EXPECT_EQ(ring.max_speed(), 0.0);
  }
}

TEST(sim_sensing, the_last_entries_of_a_ring_are_what_a_shorter_ring_fed_the_same_observations_keeps) {
  // The shared observations of exact sensing: an observer's track is the last n entries of the
  // target's ring, which must be what its own ring of capacity n would hold (the reference), with
  // the same largest speed, bit for bit; also after the target's ring was cleared.
  std::mt19937_64 random(20261203);
  constexpr std::size_t capacity = 12;
  mm::sim::detail::observation_ring shared(capacity);
  std::vector<mm::sim::detail::observation_ring> own;
  for (std::size_t n = 1; n <= capacity; ++n) own.emplace_back(n);
  std::size_t since_clear = 0;
  for (int push = 0; push < 3000; ++push) {
    if (push % 500 == 499) {
      shared.clear();
      for (auto& ring : own) ring.clear();
      since_clear = 0;
    }
    mm::observation o;
    o.time = 0.01 * push;
    o.pose.position = {0.1 * push, 0.0};
    o.speed = std::uniform_real_distribution<double>(-0.3, 9.0)(random);
    if (random() % 5 == 0) o.speed = 4.0;  // ties
    shared.push(o);
    for (auto& ring : own) ring.push(o);
    ++since_clear;
    for (std::size_t n = 0; n <= std::min(capacity, since_clear); ++n) {
      std::vector<mm::observation> last;
      shared.copy_last_to(n, last);
      ASSERT_EQ(last.size(), n) << "push " << push;
      if (n == 0) {
        EXPECT_EQ(shared.max_speed_of_last(0), 0.0);
        continue;
      }
      std::vector<mm::observation> reference;
      own[n - 1].copy_to(reference);
      ASSERT_EQ(reference.size(), n);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(last[i].time, reference[i].time) << "push " << push << ", last " << n << ", entry " << i;
        ASSERT_EQ(last[i].speed, reference[i].speed);
      }
      ASSERT_EQ(shared.max_speed_of_last(n), own[n - 1].max_speed()) << "push " << push << ", last " << n;
      ASSERT_EQ(shared.max_speed_of_last(n), own[n - 1].max_speed_by_scan());
    }
  }
}

TEST(sim_sensing, a_crashed_vehicle_keeps_the_tracks_it_had_when_it_crashed) {
  // Exact sensing keeps one ring per target; a crashed vehicle senses no more, so its tracks must
  // stay those of its last step while the others' go on (C keeps the run going).
  scenario s = crossing(false);
  planning_vehicle c = cruising("C", straight_path({0.0, 200.0}, 0.0, 400.0), 10.0);
  c.avoidance = false;
  s.planning_vehicles.push_back(c);
  simulation sim(s);
  while (sim.state(0).status != agent_status::crashed && !sim.ended()) sim.step();
  ASSERT_EQ(sim.state(0).status, agent_status::crashed);
  const mm::plan_input at_crash = *sim.planning_input(0);
  ASSERT_FALSE(at_crash.obstacles.empty());
  const double crash_time = sim.time();
  for (int k = 0; k < 60 && !sim.ended(); ++k) sim.step();
  ASSERT_GT(sim.time(), crash_time + 0.5);
  const mm::plan_input later = *sim.planning_input(0);
  ASSERT_EQ(later.obstacles.size(), at_crash.obstacles.size());
  for (std::size_t j = 0; j < later.obstacles.size(); ++j) {
    const auto& a = at_crash.obstacles[j].history;
    const auto& b = later.obstacles[j].history;
    EXPECT_EQ(later.obstacles[j].id, at_crash.obstacles[j].id);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].time, b[i].time);
      EXPECT_EQ(a[i].pose.position, b[i].pose.position);
      EXPECT_EQ(a[i].speed, b[i].speed);
    }
    EXPECT_LT(b.back().time, crash_time);
  }
}

TEST(sim_sensing, a_scene_without_planning_vehicles_runs_with_exact_sensing) {
  // Nothing observes: no shared observations are kept, and the run still goes to its end.
  scenario s = watcher({}, 0);
  s.planning_vehicles.clear();
  s.duration = 0.5;
  simulation sim(s);
  while (!sim.ended()) sim.step();
  EXPECT_NEAR(sim.time(), 0.5, 1e-9);
  EXPECT_EQ(sim.planning_vehicle_count(), 0U);
}

TEST(sim_sensing, a_track_keeps_the_history_window_and_no_more) {
  simulation sim(watcher({}, 0));
  while (sim.time() < 2.0 - 1e-9) sim.step();
  const mm::plan_input input = *sim.planning_input(0);
  const std::vector<mm::observation>& history = input.obstacles.at(0).history;
  ASSERT_EQ(history.size(), 52U);  // ⌊H/dt⌋ + 2 with H = 0.5 s and dt = 0.01 s
  EXPECT_DOUBLE_EQ(history.back().time, 2.0);
  EXPECT_NEAR(history.front().time, 1.49, 1e-9);
  for (std::size_t i = 1; i < history.size(); ++i) EXPECT_GT(history[i].time, history[i - 1].time);
  // Exact sensing: the last observation is the true state.
  EXPECT_EQ(history.back().pose.position, sim.state(1).pose.position);
  EXPECT_EQ(history.back().speed, sim.state(1).speed);
}

TEST(sim_sensing, far_agents_are_not_tracked) {
  scenario s = watcher({}, 0);
  s.scripted_vehicles[0].motion.path = path::circular_arc({0.0, 0.0}, 400.0, 0.0, pi);
  simulation sim(s);
  sim.step();
  EXPECT_TRUE(sim.planning_input(0)->obstacles.empty());
}

/// A's trajectory, bit for bit.
std::vector<double> trajectory_of(const scenario& s) {
  simulation sim(s);
  std::vector<double> out;
  run(sim, [&](const simulation& now) {
    const agent_state& a = now.state(0);
    out.insert(out.end(), {a.pose.position.x, a.pose.position.y, a.pose.heading, a.speed, a.acceleration, a.curvature});
  });
  return out;
}

TEST(sim_sensing, the_same_seed_gives_bit_identical_runs_and_another_seed_does_not) {
  scenario s = crossing(true);
  s.duration = mm::sim::testing::sanitize_scale() ? 1.2 : 2.5;
  s.noise = {0.05, 0.5 * pi / 180.0, 0.1};  // scenario S3's defaults
  s.seed = 11;
  const std::vector<double> first = trajectory_of(s);
  const std::vector<double> second = trajectory_of(s);
  ASSERT_EQ(first.size(), second.size());
  EXPECT_TRUE(first == second);  // exact equality of every double
  s.seed = 12;
  const std::vector<double> other = trajectory_of(s);
  ASSERT_EQ(first.size(), other.size());
  EXPECT_FALSE(first == other);
}

TEST(sim_sensing, noise_does_not_change_when_other_agents_are_added) {
  const sensing_noise noise{0.2, 0.05, 0.3};
  scenario alone = watcher(noise, 3);
  scenario crowded = alone;
  // Another scripted vehicle ahead of B in the list (so B's id changes) and a pedestrian.
  scripted_vehicle c = crowded.scripted_vehicles[0];
  c.name = "C";
  c.motion.path = path::circular_arc({0.0, 0.0}, 12.0, 1.0, 20.0 * pi);
  crowded.scripted_vehicles.insert(crowded.scripted_vehicles.begin(), c);
  pedestrian p;
  p.name = "P";
  p.motion.path = straight_path({5.0, 5.0}, 0.0, 50.0);
  p.motion.speed = speed_profile::constant(1.0);
  crowded.pedestrians.push_back(p);

  simulation one(alone);
  simulation many(crowded);
  const agent_id b_in_many = *many.find("B");
  ASSERT_EQ(b_in_many, 2U);
  for (int k = 0; k < 200; ++k) {
    one.step();
    many.step();
    const auto find_b = [](const mm::plan_input& input, agent_id id) {
      for (const mm::obstacle_track& t : input.obstacles) {
        if (t.id == id) return t.history.back();
      }
      return mm::observation{};
    };
    const mm::observation a = find_b(*one.planning_input(0), 1);
    const mm::observation b = find_b(*many.planning_input(0), b_in_many);
    ASSERT_EQ(a.pose.position, b.pose.position) << k;
    ASSERT_EQ(a.pose.heading, b.pose.heading) << k;
    ASSERT_EQ(a.speed, b.speed) << k;
  }
}

}  // namespace
