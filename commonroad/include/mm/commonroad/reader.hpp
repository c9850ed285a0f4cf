#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "mm/commonroad/scenario.hpp"

namespace mm::commonroad {

/// A CommonRoad file that cannot be read: the message names the file, the line, the element and
/// field, the value found and what was expected.
class read_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a CommonRoad XML file, version 2018b or 2020a (docs/commonroad.md). Throws `read_error`.
scenario read_scenario(const std::filesystem::path& file);

/// The same from the file's text; `source` names it in messages.
scenario read_scenario_text(std::string_view text, std::string_view source);

}  // namespace mm::commonroad
