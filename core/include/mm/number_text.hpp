#pragma once

#include <string>

namespace mm {

/// `value` as the shortest decimal text that reads back as the same double (std::to_chars:
/// "0.1", "1e+117", "-2.5"), or "NaN", "inf", "-inf". How every number appears in the project's
/// messages and in the files it writes, so that a number quoted in an error can be typed back.
std::string number_text(double value);

/// `value` rounded to `significant_digits` (1 to 17) significant digits in the shorter of fixed and
/// scientific notation ("2.25e-28", "0.0001", "1.5"), or "NaN", "inf", "-inf"; for messages that
/// report a derived quantity, not an input.
std::string number_text(double value, int significant_digits);

}  // namespace mm
