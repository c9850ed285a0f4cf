// The one-trapezoid path of travelled_distance against its piecewise reference, on random speeds,
// accelerations and times, many of them at or next to the times the speed reaches 0 or the cap.
#include "mm/maneuver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "property.hpp"

namespace mm {
namespace {

TEST(maneuver_property, travelled_distance_equals_its_piecewise_reference_bit_for_bit) {
  std::mt19937_64 rng(testing::property_seed() + 11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 5);
  const std::size_t count = testing::property_count(200000);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const double cap = 1.0 + 40.0 * unit(rng);
    double v0 = cap * unit(rng);
    double a = -10.0 + 14.0 * unit(rng);
    double t = 3.0 * unit(rng);
    switch (kind(rng)) {
      case 1: v0 = 0.0; break;
      case 2: v0 = cap; break;
      case 3:  // at, or one rounding step either side of, the time the speed reaches 0 or the cap
        if (a != 0.0) {
          const double reach = a < 0.0 ? -v0 / a : (cap - v0) / a;
          const int side = static_cast<int>(unit(rng) * 3.0);
          t = side == 0 ? reach : std::nextafter(reach, side == 1 ? 0.0 : 10.0);
        }
        break;
      case 4: a = 0.0; break;
      case 5: t = 0.0; break;
      default: break;
    }
    const double fast = travelled_distance(v0, a, t, cap);
    const double reference = travelled_distance_reference(v0, a, t, cap);
    ASSERT_EQ(std::signbit(fast), std::signbit(reference));
    ASSERT_EQ(fast, reference) << "trial " << trial << ": v0 " << v0 << " a " << a << " t " << t << " cap " << cap;
  }
}

}  // namespace
}  // namespace mm
