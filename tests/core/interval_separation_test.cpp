#include "mm/interval_separation.hpp"

#include <gtest/gtest.h>

namespace mm {
namespace {

TEST(interval_separation, two_cars_side_by_side_are_separated_and_two_that_meet_are_not) {
  const support_shape car{{2.25, 0.9}, 0.0};
  // Both at 10 m/s along x, 0.3 m apart side by side, for 0.1 s.
  const interval_motion ego{{{0.0, 0.0}, {1.0, 0.0}}, {{1.0, 0.0}, {1.0, 0.0}}, 0.0, 0.0};
  const interval_motion beside{{{0.0, 2.1}, {1.0, 0.0}}, {{1.0, 2.1}, {1.0, 0.0}}, 0.0, 0.0};
  const interval_separation apart = separated_throughout(car, ego, car, beside, 0.1, 0.0);
  EXPECT_TRUE(apart.separated);
  EXPECT_NEAR(apart.gap_at_end, 0.3, 1e-9);
  // A margin of 0.3 m is not kept.
  EXPECT_FALSE(separated_throughout(car, ego, car, beside, 0.1, 0.3).separated);
  // Head on, meeting within the interval: 5 m apart nose to nose, closing at 20 m/s for 0.4 s.
  const interval_motion towards{{{9.5, 0.0}, {-1.0, 0.0}}, {{5.5, 0.0}, {-1.0, 0.0}}, 0.0, 0.0};
  const interval_motion ahead{{{0.0, 0.0}, {1.0, 0.0}}, {{4.0, 0.0}, {1.0, 0.0}}, 0.0, 0.0};
  EXPECT_FALSE(separated_throughout(car, ahead, car, towards, 0.4, 0.0).separated);
  // A bound on the acceleration that could close a gap of 0.3 m in 0.1 s leaves them unproven:
  // A·0.1²/8 > 0.3 for A > 240 m/s².
  const interval_motion swerving{beside.start, beside.end, 250.0, 0.0};
  EXPECT_FALSE(separated_throughout(car, ego, car, swerving, 0.1, 0.0).separated);
  EXPECT_TRUE(separated_throughout(car, ego, car, {beside.start, beside.end, 200.0, 0.0}, 0.1, 0.0).separated);
}

}  // namespace
}  // namespace mm
