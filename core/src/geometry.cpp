#include "mm/geometry.hpp"

namespace mm {

double wrap_angle(double angle) {
  // Already in (−π, π]: std::remainder would return it unchanged (the quotient rounds to 0, ties to even).
  if (angle > -std::numbers::pi && angle <= std::numbers::pi) return angle;
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double wrapped = std::remainder(angle, two_pi);
  if (wrapped <= -std::numbers::pi) wrapped += two_pi;
  return wrapped;
}

double sinc(double x) {
  if (std::abs(x) < 1e-4) return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

double versine_ratio(double x) {
  if (std::abs(x) < 1e-4) return x / 2.0 - x * x * x / 24.0;
  const double half_sine = std::sin(x / 2.0);
  return 2.0 * half_sine * half_sine / x;
}

}  // namespace mm
