#include "mm/tool_cli.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <vector>

namespace mm::tool_cli {

namespace {

std::string in_quotes(const std::string& text) { return "'" + text + "'"; }

std::string shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string failure_message(const CLI::App& app, const CLI::Error& e) {
  std::string message = e.what();
  // An unexpected argument (a mistyped option) explains the other errors, such as a positional
  // missing or taken from the option's value, better than they do; CLI11 2.1 also lists the
  // unexpected arguments in reverse order.
  const std::vector<std::string> rest = app.remaining();
  if (!rest.empty()) {
    message = rest.size() == 1 ? "The following argument was not expected:"
                               : "The following arguments were not expected:";
    for (const std::string& argument : rest) message += " " + argument;
  }
  return app.get_name() + ": error: " + message + "\nRun with --help for more information.\n";
}

}  // namespace

std::optional<std::uint64_t> parse_whole(std::string_view text) {
  if (text.empty() || text.front() < '0' || text.front() > '9') return std::nullopt;
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<double> parse_real(std::string_view text) {
  if (text.empty() || text.front() == ' ' || text.front() == '\t' || text.front() == '\n') return std::nullopt;
  const std::string copy(text);
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<mm::sampling_resolution> parse_grid(std::string_view text) {
  const std::size_t by = text.find('x');
  if (by == std::string_view::npos) return std::nullopt;
  const std::optional<std::uint64_t> a = parse_whole(text.substr(0, by));
  const std::optional<std::uint64_t> c = parse_whole(text.substr(by + 1));
  if (!a || !c || *a < 2 || *a > mm::largest_sampling_side || *c < 1 || *c > mm::largest_sampling_side) {
    return std::nullopt;
  }
  return mm::sampling_resolution{*a, *c};
}

CLI::Validator grid_of_samples() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (parse_grid(text)) return {};
        const std::string side = std::to_string(mm::largest_sampling_side);
        return "expected AxC, A accelerations per family from 2 to " + side + " and C curvatures from 1 to " +
               side + " (e.g. 14x19), got " + in_quotes(text);
      },
      "");
}

CLI::Validator whole_number(std::uint64_t min, std::uint64_t max) {
  std::string expected;
  if (min == 0 && max == 1) {
    expected = "0 or 1";
  } else if (max == unbounded) {
    expected = "a whole number >= " + std::to_string(min);
  } else {
    expected = "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  }
  return CLI::Validator(
      [min, max, expected](std::string& text) -> std::string {
        const std::optional<std::uint64_t> value = parse_whole(text);
        if (value && *value >= min && *value <= max) return {};
        return "expected " + expected + ", got " + in_quotes(text);
      },
      "");
}

CLI::Validator real_number(real_bound bound, std::string unit) {
  const std::string expected = std::string(bound == real_bound::positive ? "a number > 0" : "a number >= 0") +
                               (unit.empty() ? "" : " [" + unit + "]");
  return CLI::Validator(
      [bound, expected](std::string& text) -> std::string {
        const std::optional<double> value = parse_real(text);
        if (value && (bound == real_bound::positive ? *value > 0.0 : *value >= 0.0)) return {};
        return "expected " + expected + ", got " + in_quotes(text);
      },
      "");
}

CLI::Option* add_real(CLI::App& app, const std::string& name, double& target, real_bound bound, const std::string& unit,
                      const std::string& description, const std::string& type_name) {
  return app
      .add_option_function<std::string>(
          name, [&target](const std::string& text) { target = *parse_real(text); }, description)
      ->check(real_number(bound, unit))
      ->type_name(type_name)
      ->default_str(shortest(target));
}

CLI::Option* add_real(CLI::App& app, const std::string& name, std::optional<double>& target, real_bound bound,
                      const std::string& unit, const std::string& description, const std::string& type_name) {
  return app
      .add_option_function<std::string>(
          name, [&target](const std::string& text) { target = *parse_real(text); }, description)
      ->check(real_number(bound, unit))
      ->type_name(type_name);
}

int run(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  app.failure_message([](const CLI::App* failed, const CLI::Error& e) { return failure_message(*failed, e); });
  try {
    app.parse(argc, argv);
    return body();
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : exit_bad_input;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::cerr << app.get_name() << ": error: " << e.what() << "\n";
    return exit_bad_input;
  }
}

}  // namespace mm::tool_cli
