#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace mm::sim::detail {

/// A number in a message: the shortest decimal text that reads back as `value`, or NaN, inf, -inf.
inline std::string number_text(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace mm::sim::detail
