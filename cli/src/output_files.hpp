#pragma once
// What the commands that write output files share (docs/outputs.md): JSON numbers rounded to a
// few decimals, footprints as JSON, and whole-file writes that report failure.

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>

#include "mm/drivable_area.hpp"
#include "mm/footprint.hpp"
#include "mm/geometry.hpp"

namespace mm::cli::output {

using json = nlohmann::ordered_json;

/// `value` rounded to `decimals` decimals, so that JSON shows e.g. 1.23 rather than 1.2300000000000002.
inline double rounded(double value, int decimals = 6) {
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(value * scale) / scale;
  return r == 0.0 ? 0.0 : r;
}

/// A scene coordinate pair [m], to 4 decimals.
inline json point(vec2 p) { return json::array({rounded(p.x, 4), rounded(p.y, 4)}); }

/// scene.json's `drivable_area`: the boundary of the road constraint's area as segments
/// [[[x, y], [x, y]], ...] (what a plot draws as the road's edges), or null without one.
inline json drivable_area_json(const std::shared_ptr<const mm::drivable_area>& area) {
  if (!area) return nullptr;
  json segments = json::array();
  for (const mm::segment& s : area->boundary()) segments.push_back(json::array({point(s.a), point(s.b)}));
  return {{"boundary_m", segments}};
}

/// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180; a line break
/// becomes a space).
inline std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += "\"\"";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "\"";
}

/// The points of a polygon or path, each as `point`.
inline json points(std::span<const vec2> ps) {
  json out = json::array();
  for (vec2 p : ps) out.push_back(point(p));
  return out;
}

/// {"shape": "rectangle", "length_m", "width_m"}, {"shape": "disc", "radius_m"} or
/// {"shape": "polygon", "vertices_m"} (body frame).
inline json footprint_json(const mm::footprint& shape) {
  if (const auto* r = std::get_if<mm::rectangle>(&shape)) {
    return {{"shape", "rectangle"}, {"length_m", rounded(r->length, 4)}, {"width_m", rounded(r->width, 4)}};
  }
  if (const auto* d = std::get_if<mm::disc>(&shape)) return {{"shape", "disc"}, {"radius_m", rounded(d->radius, 4)}};
  return {{"shape", "polygon"}, {"vertices_m", points(std::get<mm::convex_polygon>(shape).vertices)}};
}

/// Writes `text` to `file`; throws std::runtime_error naming the file and the reason when that fails.
inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write the file: " + std::strerror(errno));
}

}  // namespace mm::cli::output
