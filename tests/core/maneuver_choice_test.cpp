#include "mm/maneuver_choice.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace mm {
namespace {

struct fixture {
  ego_state ego;
  maneuver_samples samples;
  sample_mask colliding;
  choice_input input;

  explicit fixture(double nominal_curvature = 0.0) {
    ego.speed = 10.0;
    samples = sample_maneuvers(ego, nominal_curvature, 1.0, {8, 5});
    colliding = sample_mask(samples.size());
    input.samples = &samples;
    input.colliding = &colliding;
    input.nominal = {0.5, nominal_curvature};
    input.initial_speed = ego.speed;
  }
  void collide_where(auto predicate) {
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (predicate(samples.maneuvers[m])) colliding.set(m);
    }
  }
};

TEST(maneuver_choice, a_safe_nominal_maneuver_is_applied_unchanged) {
  fixture f;
  f.input.nominal_safe = true;
  const auto d = choose_maneuver(f.input);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->mode, planning_mode::nominal);
  EXPECT_EQ(d->command, (maneuver{0.5, 0.0}));
}

TEST(maneuver_choice, minimal_effort_picks_the_safe_maneuver_closest_to_the_nominal) {
  fixture f;
  // Everything above −2 m/s² collides: the least change is braking at −2 m/s², straight ahead.
  f.collide_where([](const maneuver& u) { return u.acceleration > -2.0; });
  const auto d = choose_maneuver(f.input);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->mode, planning_mode::avoid);
  EXPECT_EQ(d->command.acceleration, -2.0);  // brake nodes are 0, −1, …, −7
  EXPECT_EQ(d->command.curvature, 0.0);
}

TEST(maneuver_choice, lateral_effort_is_weighted_by_the_squared_speed) {
  fixture f;
  EXPECT_DOUBLE_EQ(maneuver_effort({0.5, 0.01}, {0.5, 0.0}, 10.0, {}), 1.0);
  EXPECT_DOUBLE_EQ(maneuver_effort({-1.5, 0.0}, {0.5, 0.0}, 10.0, {}), 4.0);
  EXPECT_DOUBLE_EQ(maneuver_effort({-1.5, 0.01}, {0.5, 0.0}, 10.0, {2.0, 3.0}), 11.0);
}

TEST(maneuver_choice, an_empty_selected_family_falls_back_to_the_other_family) {
  fixture f;
  f.collide_where([](const maneuver& u) { return u.acceleration < 2.0; });
  f.input.selected_family = family::brake;
  const auto d = choose_maneuver(f.input);
  ASSERT_TRUE(d);
  EXPECT_GE(d->command.acceleration, 2.0);
  EXPECT_EQ(d->mode, planning_mode::avoid);
}

TEST(maneuver_choice, urgent_steering_takes_maximal_effort_when_no_straight_escape_exists) {
  fixture f;
  // Only strong left steering is safe: the nominal-curvature columns all collide.
  f.collide_where([](const maneuver& u) { return u.curvature < 0.02; });
  f.input.urgent_steering = true;
  const auto urgent = choose_maneuver(f.input);
  ASSERT_TRUE(urgent);
  EXPECT_EQ(urgent->mode, planning_mode::urgent);
  EXPECT_EQ(urgent->command.acceleration, -7.0);
  EXPECT_DOUBLE_EQ(urgent->command.curvature, 0.05);
  f.input.urgent_steering = false;
  const auto calm = choose_maneuver(f.input);
  ASSERT_TRUE(calm);
  EXPECT_EQ(calm->mode, planning_mode::avoid);
  EXPECT_DOUBLE_EQ(calm->command.curvature, 0.025);
  EXPECT_DOUBLE_EQ(calm->command.acceleration, 0.0);
}

TEST(maneuver_choice, urgent_steering_stays_minimal_when_a_nominal_curvature_maneuver_is_safe) {
  fixture f;
  f.collide_where([](const maneuver& u) { return u.acceleration > -4.0; });
  f.input.urgent_steering = true;
  const auto d = choose_maneuver(f.input);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->mode, planning_mode::avoid);
  EXPECT_EQ(d->command, (maneuver{-4.0, 0.0}));
}

TEST(maneuver_choice, the_nominal_curvature_column_is_a_candidate_between_grid_curvatures) {
  fixture f(0.013);  // between the grid curvatures 0 and 0.025
  f.collide_where([](const maneuver& u) { return u.acceleration > -1.0; });
  const auto d = choose_maneuver(f.input);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->command, (maneuver{-1.0, 0.013}));
}

TEST(maneuver_choice, nothing_safe_yields_no_decision_and_near_crash_takes_the_latest_collision) {
  fixture f;
  f.collide_where([](const maneuver&) { return true; });
  EXPECT_FALSE(choose_maneuver(f.input));
  std::vector<double> first(f.samples.size(), 1.0);
  const std::vector<double> none(f.samples.size(), std::numeric_limits<double>::infinity());
  first[7] = 1.4;
  first[12] = 1.4;  // as late as sample 7; the one that brakes harder wins
  const maneuver_decision d = near_crash_maneuver(f.samples, first, none, 0.0);
  EXPECT_EQ(d.mode, planning_mode::near_crash);
  const std::size_t harder = f.samples.maneuvers[12].acceleration < f.samples.maneuvers[7].acceleration ? 12 : 7;
  EXPECT_EQ(d.sample, harder);
  first[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(near_crash_maneuver(f.samples, first, none, 0.0).sample, 3u);
}

TEST(maneuver_choice, near_crash_ties_at_the_hardest_braking_go_to_the_latest_contact_of_the_bodies) {
  fixture f(0.0);
  f.collide_where([](const maneuver&) { return true; });
  // Inside the margin: every maneuver collides at t = 0, so the hardest braking wins, and among those
  // the steering change alone would keep the nominal curvature.
  const std::vector<double> at_once(f.samples.size(), 0.0);
  std::vector<double> contact(f.samples.size(), 0.5);
  std::size_t hardest = 0;
  for (std::size_t m = 0; m < f.samples.size(); ++m) {
    if (f.samples.maneuvers[m].acceleration < f.samples.maneuvers[hardest].acceleration) hardest = m;
  }
  const maneuver_decision by_steering = near_crash_maneuver(f.samples, at_once, contact, 0.0);
  EXPECT_EQ(by_steering.command.acceleration, f.samples.maneuvers[hardest].acceleration);
  EXPECT_EQ(by_steering.command.curvature, 0.0);
  // A maneuver of that braking that touches later (here never) wins, steering or not.
  std::size_t steering = f.samples.size();
  for (std::size_t m = 0; m < f.samples.size(); ++m) {
    const maneuver& u = f.samples.maneuvers[m];
    if (u.acceleration == f.samples.maneuvers[hardest].acceleration && u.curvature > 0.0) steering = m;
  }
  ASSERT_LT(steering, f.samples.size());
  contact[steering] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(near_crash_maneuver(f.samples, at_once, contact, 0.0).sample, steering);
  // A maneuver that brakes less is not preferred for touching later.
  std::size_t softer = f.samples.size();
  for (std::size_t m = 0; m < f.samples.size(); ++m) {
    if (f.samples.maneuvers[m].acceleration > f.samples.maneuvers[hardest].acceleration) softer = m;
  }
  contact.assign(f.samples.size(), 0.5);
  contact[softer] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(near_crash_maneuver(f.samples, at_once, contact, 0.0).command.acceleration,
            f.samples.maneuvers[hardest].acceleration);
}

}  // namespace
}  // namespace mm
