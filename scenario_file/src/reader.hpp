#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mm/geometry.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/scenario.hpp"

namespace mm::scenario_file::detail {

/// One unit a quantity may be written in: the key suffix and the factor to SI.
struct unit {
  std::string_view suffix;  ///< e.g. "_kmh"
  double to_si = 1.0;       ///< SI value = file value × to_si
  std::string_view label;   ///< e.g. "km/h", for messages
};

using units = std::initializer_list<unit>;

inline constexpr unit metres{"_m", 1.0, "m"};
inline constexpr unit seconds{"_s", 1.0, "s"};
inline constexpr unit kmh{"_kmh", 1.0 / 3.6, "km/h"};
inline constexpr unit mps{"_mps", 1.0, "m/s"};
inline constexpr unit mps2{"_mps2", 1.0, "m/s²"};
inline constexpr unit per_second{"_per_s", 1.0, "1/s"};
inline constexpr unit per_metre{"_per_m", 1.0, "1/m"};
inline constexpr unit degrees{"_deg", 0.017453292519943295, "°"};
inline constexpr unit radians{"_rad", 1.0, "rad"};

/// Allowed ranges of numbers (checked on the value as written).
/// `size`: the size of a footprint, at least `smallest_size`; `speed`: from 0 to `largest_speed`
/// (in SI units), `positive_speed` above 0: road users' sizes and speeds
/// (`mm::sim::smallest_road_user_size`, `largest_road_user_speed`).
enum class range : std::uint8_t { any, non_negative, positive, size, speed, positive_speed, noise };
inline constexpr double smallest_size = mm::sim::smallest_road_user_size;  ///< [m]
inline constexpr double largest_speed = mm::sim::largest_road_user_speed;  ///< [m/s]

/// Where the loader is: the source name and the parameters fields may reference.
struct context {
  std::string source;
  std::vector<parameter> parameters;

  [[noreturn]] void fail(const YAML::Node& where, const std::string& field, const std::string& problem) const;
  const parameter* find_parameter(std::string_view name) const;
};

/// A YAML node and the field path that leads to it (`agents[0].path.segments[2]`).
///
/// Assignment re-seats the reference (`YAML::Node::reset`): yaml-cpp's own `operator=` writes
/// the right-hand node's value into the node referred to, which would rewrite the document.
struct field {
  YAML::Node node;
  std::string path;
  std::string key;  ///< the last map key on the path ("" for sequence items)

  field() = default;
  field(const YAML::Node& n, std::string p, std::string k) : node(n), path(std::move(p)), key(std::move(k)) {}
  field(const field&) = default;
  field& operator=(const field& other) {
    node.reset(other.node);
    path = other.path;
    key = other.key;
    return *this;
  }
  ~field() = default;
};

/// The closest of `candidates` to `word` when it is a plausible typo of it, else "".
std::string closest(std::string_view word, const std::vector<std::string>& candidates);

/// What a message about the unknown name `word` adds: "; did you mean X?" for a plausible typo of
/// one of `candidates`, else "; did you mean A or B?" for the (at most three) candidates that have
/// every one of its `_`-separated words (`speed_kmh`: `initial_speed_kmh`, `desired_speed_kmh`), else
/// "; expected one of " and every candidate. "" when there are none.
std::string unknown_name_hint(std::string_view word, const std::vector<std::string>& candidates);

/// How a node is shown in messages: the scalar as written, `$p (= 40)` for references, or a
/// description of a map, list or nothing.
std::string shown(const context& ctx, const YAML::Node& node);

/// `field` = value: expected `what` — thrown at the field's node.
[[noreturn]] void fail_value(const context& ctx, const field& f, const std::string& what);

/// Reads a number: a plain scalar or `$parameter`; the parameter's unit (its name's suffix)
/// must match the field's unit suffix. `label` describes the unit for messages ("km/h", "" none).
/// `to_si`: the factor from the field's unit to SI, for `range::speed`.
double read_number(const context& ctx, const field& f, std::string_view label, range r = range::any, double to_si = 1.0);
/// A non-negative integer (`$parameter` allowed if integral) up to `max`.
std::uint64_t read_integer(const context& ctx, const field& f, std::uint64_t max);
bool read_bool(const context& ctx, const field& f);
/// A plain string scalar (no parameter references).
std::string read_string(const context& ctx, const field& f);
/// `[x, y]` [m].
vec2 read_point(const context& ctx, const field& f);
/// A list of `[x, y]` [m], at least `min_count` (and at most `max_count`) points.
std::vector<vec2> read_points(const context& ctx, const field& f, std::size_t min_count, std::size_t max_count);
/// One of `names`, returned as its index.
std::size_t read_choice(const context& ctx, const field& f, std::initializer_list<std::string_view> names);
/// The items of a list.
std::vector<field> read_list(const context& ctx, const field& f);

/// A map read through layers: the most specific first (an agent, then `defaults.<kind>`). A key
/// is taken from the first layer that has it. Every layer must be a map (or absent) and may hold
/// only the keys given to `allow`.
class map_view {
 public:
  /// `layers[0]` must be present; later layers may be undefined nodes.
  map_view(const context& ctx, std::vector<field> layers);

  /// Checks every layer for keys outside `keys` (unknown keys are errors, with a suggestion).
  const map_view& allow(const std::vector<std::string>& keys) const;

  bool has(std::string_view key) const;
  std::optional<field> get(std::string_view key) const;
  /// The key, which must be present (else "missing required field").
  field require(std::string_view key) const;
  /// The nested map under `key` in every layer that has it (each must be a map).
  map_view child(std::string_view key) const;
  /// The first layer's node and path: where "missing" errors point.
  const field& self() const { return layers_.front(); }

  /// A quantity written as `base` + one of `alternatives` (at most one per layer), converted to
  /// SI; none if no layer has it.
  std::optional<double> quantity(std::string_view base, units alternatives, range r = range::any) const;
  double quantity_or(std::string_view base, units alternatives, double fallback, range r = range::any) const;
  double required_quantity(std::string_view base, units alternatives, range r = range::any) const;

  /// Which of `keys` (mutually exclusive) is given in the most specific layer that has one; none.
  std::optional<field> one_of(const std::vector<std::string>& keys) const;

  const context& ctx() const { return *ctx_; }

 private:
  const context* ctx_;
  std::vector<field> layers_;
  YAML::Node anchor_;  ///< where "missing" errors point: the first layer, or the parent of an absent map
};

/// True when `text` is well-formed UTF-8 (no overlong forms, surrogates or code points above U+10FFFF).
bool is_utf8(std::string_view text);

/// Every key `base` + suffix for `alternatives`, for `allow` lists.
std::vector<std::string> keys_of(std::string_view base, units alternatives);

}  // namespace mm::scenario_file::detail
