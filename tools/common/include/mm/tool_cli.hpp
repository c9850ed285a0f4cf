#pragma once

#include <CLI/CLI.hpp>

#include <concepts>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "mm/planner_config.hpp"

namespace mm::tool_cli {

/// Exit code of the developer tools for an invalid command line or bad input (a file, a value).
inline constexpr int exit_bad_input = 2;

/// The upper bound of a whole number without one.
inline constexpr std::uint64_t unbounded = std::numeric_limits<std::uint64_t>::max();

/// `text` as a whole decimal number (digits only, no sign), none when it is not one or exceeds 2⁶⁴ − 1.
std::optional<std::uint64_t> parse_whole(std::string_view text);

/// `text` as a finite real number, read as std::strtod (and so std::atof) reads it, all of it; none otherwise.
std::optional<double> parse_real(std::string_view text);

/// `text` as a planner's sampling grid as a command line writes it, "AxC": A accelerations per family
/// (2 to `mm::largest_sampling_side`), C curvatures (1 to it); none otherwise.
std::optional<mm::sampling_resolution> parse_grid(std::string_view text);

/// Accepts "AxC" as `parse_grid` reads it; its error message says what is expected and quotes the value.
CLI::Validator grid_of_samples();

/// Accepts a whole number from `min` to `max` (or `unbounded`); its error message says so and quotes the value.
CLI::Validator whole_number(std::uint64_t min, std::uint64_t max);

/// Which real numbers an option accepts.
enum class real_bound { positive, non_negative };

/// Accepts a finite real number > 0 or ≥ 0, in `unit` (as in "[s]", named in the error message).
CLI::Validator real_number(real_bound bound, std::string unit);

/// Adds `name`, a whole number from `min` to `max` stored in `target`; `target`'s value is the default
/// shown by --help.
template <std::integral T>
CLI::Option* add_whole(CLI::App& app, const std::string& name, T& target, std::uint64_t min, std::uint64_t max,
                       const std::string& description, const std::string& type_name = "N") {
  return app
      .add_option_function<std::string>(
          name, [&target](const std::string& text) { target = static_cast<T>(*parse_whole(text)); }, description)
      ->check(whole_number(min, max))
      ->type_name(type_name)
      ->default_str(std::to_string(target));
}

/// Adds `name`, a real number in `unit` stored in `target` (read as std::atof reads it), shown with
/// `target`'s value as its default.
CLI::Option* add_real(CLI::App& app, const std::string& name, double& target, real_bound bound, const std::string& unit,
                      const std::string& description, const std::string& type_name);

/// As `add_real`, for an option without a default.
CLI::Option* add_real(CLI::App& app, const std::string& name, std::optional<double>& target, real_bound bound,
                      const std::string& unit, const std::string& description, const std::string& type_name);

/// Parses the command line into `app` (whose name is the tool's) and runs `body`. Returns `body`'s
/// exit code; 0 after printing the usage for --help; `exit_bad_input` after printing
/// "<tool>: error: <message>" to standard error for an invalid command line (also a CLI::ParseError
/// thrown by `body`, for checks across options) or a std::exception thrown by `body` (a file that
/// cannot be read, a scenario error, an agent that does not exist).
int run(CLI::App& app, int argc, char** argv, const std::function<int()>& body);

}  // namespace mm::tool_cli
