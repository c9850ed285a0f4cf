// The numbers of the CSV outputs: `fixed` (std::to_chars) against fmt's "{:.Nf}", the reference.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "mm/cli/commands.hpp"

namespace {

/// The reference: fmt's correctly rounded fixed notation, "-0.000" written "0.000", "" when not finite.
std::string fixed_reference(double value, int decimals) {
  if (!std::isfinite(value)) return {};
  std::string text = fmt::format("{:.{}f}", value, decimals);
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

TEST(commands, fixed_writes_the_characters_of_fmts_fixed_notation_on_random_values) {
  const std::uint64_t seed = 20261202;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> exponent(-12.0, 12.0);
  std::uniform_int_distribution<int> decimals(0, 9);
  for (int n = 0; n < 200000; ++n) {
    const double magnitude = std::pow(10.0, exponent(random));
    const double value = (n % 2 == 0 ? 1.0 : -1.0) * magnitude;
    const int d = n % 3 == 0 ? 6 : decimals(random);
    ASSERT_EQ(mm::cli::fixed(value, d), fixed_reference(value, d))
        << "seed " << seed << ", value " << fmt::format("{:.17g}", value) << ", decimals " << d;
  }
}

TEST(commands, fixed_writes_ties_negative_zeros_extremes_and_non_finite_values_as_the_reference) {
  const double values[] = {0.0,
                           -0.0,
                           -0.0000004,
                           -0.0000005,
                           0.0000005,
                           0.0000015,
                           2.5,
                           -2.5,
                           0.125,
                           1e300,
                           -1e300,
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()};
  for (const double value : values) {
    for (const int d : {0, 1, 2, 3, 6, 17}) {
      EXPECT_EQ(mm::cli::fixed(value, d), fixed_reference(value, d)) << fmt::format("{:.17g}", value) << ", " << d;
    }
  }
  EXPECT_EQ(mm::cli::fixed(-0.0000004), "0.000000");
  EXPECT_EQ(mm::cli::fixed(std::numeric_limits<double>::infinity()), "");
}

}  // namespace
