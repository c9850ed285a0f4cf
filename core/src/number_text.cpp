#include "mm/number_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

namespace mm {
namespace {

/// "NaN", "inf" or "-inf" for a value that is not finite; empty for a finite one.
std::string not_finite(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  return {};
}

}  // namespace

std::string number_text(double value) {
  if (!std::isfinite(value)) return not_finite(value);
  std::array<char, 32> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value).ptr;
  return std::string(buffer.data(), end);
}

std::string number_text(double value, int significant_digits) {
  if (!std::isfinite(value)) return not_finite(value);
  std::array<char, 40> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general,
                                 std::clamp(significant_digits, 1, 17))
                       .ptr;
  return std::string(buffer.data(), end);
}

}  // namespace mm
