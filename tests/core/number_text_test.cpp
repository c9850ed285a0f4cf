#include "mm/number_text.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace mm {
namespace {

double read_back(const std::string& text) {
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  EXPECT_EQ(result.ec, std::errc{}) << text;
  EXPECT_EQ(result.ptr, text.data() + text.size()) << text;
  return value;
}

TEST(number_text, writes_the_shortest_decimal_that_reads_back) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(40.0), "40");
  EXPECT_EQ(number_text(-2.5), "-2.5");
  EXPECT_EQ(number_text(1e117), "1e+117");
  EXPECT_EQ(number_text(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(number_text(-0.0), "-0");
}

TEST(number_text, reads_back_bit_for_bit_on_random_doubles) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    const std::uint64_t bits = rng();
    double value = 0.0;
    static_assert(sizeof value == sizeof bits);
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    const std::string text = number_text(value);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(read_back(text)), bits) << "bits " << bits << " written as " << text;
  }
}

TEST(number_text, names_values_that_are_not_finite) {
  EXPECT_EQ(number_text(std::numeric_limits<double>::quiet_NaN()), "NaN");
  EXPECT_EQ(number_text(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(number_text(std::numeric_limits<double>::quiet_NaN(), 3), "NaN");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity(), 3), "-inf");
}

TEST(number_text, rounds_to_the_significant_digits_asked_for) {
  EXPECT_EQ(number_text(2.2468e-28, 3), "2.25e-28");
  EXPECT_EQ(number_text(0.0001, 3), "0.0001");
  EXPECT_EQ(number_text(1.23456789, 6), "1.23457");
  EXPECT_EQ(number_text(123456.0, 3), "1.23e+05");
  EXPECT_EQ(number_text(1.5, 4), "1.5");
  EXPECT_EQ(number_text(1.0 / 3.0, 0), "0.3") << "fewer than one digit is one";
  EXPECT_EQ(number_text(1.0 / 3.0, 40), number_text(1.0 / 3.0, 17)) << "more than 17 digits is 17";
}

}  // namespace
}  // namespace mm
