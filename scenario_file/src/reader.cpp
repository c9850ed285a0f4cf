#include "reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include "mm/number_text.hpp"

namespace mm::scenario_file::detail {
namespace {

/// Unit suffixes of field and parameter names, longest first where one ends another.
constexpr std::string_view unit_suffixes[] = {"_per_s", "_mps2", "_kmh", "_mps", "_deg", "_rad", "_m", "_s"};

std::string_view unit_suffix(std::string_view name) {
  for (std::string_view suffix : unit_suffixes) {
    if (name.size() > suffix.size() && name.substr(name.size() - suffix.size()) == suffix) return suffix;
  }
  return {};
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0U : 1U)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::optional<double> parse_double(std::string_view text) {
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

/// The key of a map entry as text; error when it is not a plain scalar.
std::string key_text(const context& ctx, const field& map, const YAML::Node& key) {
  if (!key.IsScalar()) ctx.fail(key, map.path, "expected a key name, found " + shown(ctx, key));
  return key.Scalar();
}

std::string join(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string unit_text(std::string_view label) { return label.empty() ? "" : " [" + std::string(label) + "]"; }

}  // namespace

void context::fail(const YAML::Node& where, const std::string& field, const std::string& problem) const {
  int line = 0;
  int column = 0;
  if (where.IsDefined()) {
    const YAML::Mark mark = where.Mark();
    if (mark.line >= 0) {
      line = mark.line + 1;
      column = mark.column + 1;
    }
  }
  throw scenario_error(source, line, column, field, problem);
}

const parameter* context::find_parameter(std::string_view name) const {
  for (const parameter& p : parameters) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  const std::size_t allowed = std::max<std::size_t>(2, word.size() / 3);
  return best_distance <= allowed ? best : std::string();
}

std::string unknown_name_hint(std::string_view word, const std::vector<std::string>& candidates) {
  if (candidates.empty()) return {};
  if (std::string typo = closest(word, candidates); !typo.empty()) return "; did you mean " + typo + "?";
  const auto words_of = [](std::string_view name) {
    std::vector<std::string_view> parts;
    for (std::size_t start = 0; start <= name.size();) {
      const std::size_t end = std::min(name.find('_', start), name.size());
      if (end > start) parts.push_back(name.substr(start, end - start));
      start = end + 1;
    }
    return parts;
  };
  const std::vector<std::string_view> wanted = words_of(word);
  std::vector<std::string> containing;
  for (const std::string& c : candidates) {
    const std::vector<std::string_view> have = words_of(c);
    const bool all = !wanted.empty() && std::all_of(wanted.begin(), wanted.end(), [&](std::string_view w) {
      return std::find(have.begin(), have.end(), w) != have.end();
    });
    if (all) containing.push_back(c);
  }
  if (!containing.empty() && containing.size() <= 3) {
    std::string text = "; did you mean ";
    for (std::size_t i = 0; i < containing.size(); ++i) {
      text += (i == 0 ? "" : i + 1 == containing.size() ? " or " : ", ") + containing[i];
    }
    return text + "?";
  }
  std::string text = "; expected one of ";
  for (std::size_t i = 0; i < candidates.size(); ++i) text += (i == 0 ? "" : ", ") + candidates[i];
  return text;
}

std::string shown(const context& ctx, const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "<nothing>";
  if (node.IsMap()) return "<a map>";
  if (node.IsSequence()) return "<a list>";
  const std::string& text = node.Scalar();
  if (!text.empty() && text[0] == '$') {
    if (const parameter* p = ctx.find_parameter(std::string_view(text).substr(1))) {
      return text + " (= " + number_text(p->value) + ")";
    }
  }
  std::string out = text.size() > 60 ? text.substr(0, 57) + "..." : text;
  const bool quote = out.empty() || out.find_first_of(" :,#") != std::string::npos;
  return quote ? "\"" + out + "\"" : out;
}

void fail_value(const context& ctx, const field& f, const std::string& what) {
  ctx.fail(f.node, f.path, "= " + shown(ctx, f.node) + ": expected " + what);
}

double read_number(const context& ctx, const field& f, std::string_view label, range r, double to_si) {
  const std::string expected =
      r == range::noise ? "a standard deviation from 0 to " + number_text(mm::sim::largest_noise_sd / to_si) + unit_text(label)
      : r == range::speed || r == range::positive_speed
          ? std::string(r == range::speed ? "a speed from 0" : "a speed above 0") + " to " +
                number_text(largest_speed / to_si) + unit_text(label) + " (" + number_text(largest_speed) + " m/s)"
                        : std::string(r == range::positive       ? "a positive number"
                                      : r == range::non_negative ? "a number ≥ 0"
                                      : r == range::size         ? "a size from " + number_text(smallest_size) + " to " +
                                                                       number_text(mm::largest_footprint_size)
                                                                 : "a number") +
                              unit_text(label);
  if (!f.node.IsScalar()) fail_value(ctx, f, expected);
  const std::string& text = f.node.Scalar();
  double value = 0.0;
  if (!text.empty() && text[0] == '$') {
    const std::string name = text.substr(1);
    const parameter* p = ctx.find_parameter(name);
    if (p == nullptr) {
      std::vector<std::string> names;
      for (const parameter& q : ctx.parameters) names.push_back(q.name);
      const std::string hint = closest(name, names);
      fail_value(ctx, f, "a number or a parameter of the `parameters:` map; there is no parameter \"" + name + "\"" +
                             (hint.empty() ? "" : " (did you mean $" + hint + "?)"));
    }
    const std::string_view parameter_unit = unit_suffix(name);
    const std::string_view field_unit = unit_suffix(f.key);
    if (!parameter_unit.empty() && parameter_unit != field_unit) {
      fail_value(ctx, f,
                 "a value in the field's unit: parameter " + name + " is in \"" + std::string(parameter_unit) +
                     "\" units, the field " + f.key + " in " +
                     (field_unit.empty() ? std::string("none") : "\"" + std::string(field_unit) + "\""));
    }
    value = p->value;
  } else {
    const std::optional<double> parsed = parse_double(text);
    if (!parsed) fail_value(ctx, f, expected);
    value = *parsed;
  }
  if (!std::isfinite(value)) fail_value(ctx, f, "a finite number" + unit_text(label));
  if ((r == range::non_negative && !(value >= 0.0)) || (r == range::positive && !(value > 0.0)) ||
      (r == range::size && !(value >= smallest_size && value <= mm::largest_footprint_size)) ||
      (r == range::speed && !(value >= 0.0 && value * to_si <= largest_speed)) ||
      (r == range::positive_speed && !(value > 0.0 && value * to_si <= largest_speed)) ||
      (r == range::noise && !(value >= 0.0 && value * to_si <= mm::sim::largest_noise_sd))) {
    fail_value(ctx, f, expected);
  }
  return value;
}

std::uint64_t read_integer(const context& ctx, const field& f, std::uint64_t max) {
  const std::string expected = "an integer from 0 to " + std::to_string(max);
  if (!f.node.IsScalar()) fail_value(ctx, f, expected);
  const std::string& text = f.node.Scalar();
  if (!text.empty() && text[0] == '$') {
    const double value = read_number(ctx, f, "");
    // 2^53: beyond it a double no longer holds every integer (and the cast could overflow).
    const double largest = std::min(static_cast<double>(max), 9007199254740992.0);
    if (!(value >= 0.0 && value <= largest && value == std::floor(value))) fail_value(ctx, f, expected);
    return static_cast<std::uint64_t>(value);
  }
  std::uint64_t value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size() || value > max) {
    fail_value(ctx, f, expected);
  }
  return value;
}

bool read_bool(const context& ctx, const field& f) {
  if (f.node.IsScalar()) {
    const std::string& text = f.node.Scalar();
    if (text == "true") return true;
    if (text == "false") return false;
    if (!text.empty() && text[0] == '$') {
      const double value = read_number(ctx, f, "");
      if (value == 0.0 || value == 1.0) return value == 1.0;
      fail_value(ctx, f, "true or false (a parameter must be 1 for true or 0 for false)");
    }
  }
  fail_value(ctx, f, "true or false (or a parameter that is 1 or 0)");
}

bool is_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = byte(i);
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xBF;
    if (c < 0x80) {
      ++i;
      continue;
    }
    if (c >= 0xC2 && c <= 0xDF) length = 2;
    else if (c >= 0xE0 && c <= 0xEF) length = 3, low = c == 0xE0 ? 0xA0 : 0x80, high = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) length = 4, low = c == 0xF0 ? 0x90 : 0x80, high = c == 0xF4 ? 0x8F : 0xBF;
    else return false;
    if (i + length > text.size()) return false;
    if (byte(i + 1) < low || byte(i + 1) > high) return false;
    for (std::size_t k = 2; k < length; ++k) {
      if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return false;
    }
    i += length;
  }
  return true;
}

std::string read_string(const context& ctx, const field& f) {
  if (!f.node.IsScalar()) fail_value(ctx, f, "a text");
  if (!is_utf8(f.node.Scalar())) {
    ctx.fail(f.node, f.path, "a text that is not UTF-8: expected UTF-8 text (a YAML file is Unicode)");
  }
  return f.node.Scalar();
}

vec2 read_point(const context& ctx, const field& f) {
  if (!f.node.IsSequence() || f.node.size() != 2) fail_value(ctx, f, "a point [x, y] in metres");
  const field x{f.node[0], f.path + "[0]", f.key};
  const field y{f.node[1], f.path + "[1]", f.key};
  return {read_number(ctx, x, "m"), read_number(ctx, y, "m")};
}

std::vector<vec2> read_points(const context& ctx, const field& f, std::size_t min_count, std::size_t max_count) {
  const std::string expected = "a list of " + std::to_string(min_count) + " to " + std::to_string(max_count) +
                               " points [x, y] in metres";
  if (!f.node.IsSequence() || f.node.size() < min_count || f.node.size() > max_count) fail_value(ctx, f, expected);
  std::vector<vec2> points;
  for (std::size_t i = 0; i < f.node.size(); ++i) {
    points.push_back(read_point(ctx, {f.node[i], f.path + "[" + std::to_string(i) + "]", f.key}));
  }
  return points;
}

std::size_t read_choice(const context& ctx, const field& f, std::initializer_list<std::string_view> names) {
  std::string expected = "one of";
  std::vector<std::string> candidates;
  for (std::string_view n : names) {
    expected += (candidates.empty() ? " " : ", ") + std::string(n);
    candidates.emplace_back(n);
  }
  if (f.node.IsScalar()) {
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (f.node.Scalar() == candidates[i]) return i;
    }
    const std::string hint = closest(f.node.Scalar(), candidates);
    if (!hint.empty()) expected += " (did you mean " + hint + "?)";
  }
  fail_value(ctx, f, expected);
}

std::vector<field> read_list(const context& ctx, const field& f) {
  if (!f.node.IsSequence()) fail_value(ctx, f, "a list");
  std::vector<field> items;
  for (std::size_t i = 0; i < f.node.size(); ++i) items.push_back({f.node[i], f.path + "[" + std::to_string(i) + "]", f.key});
  return items;
}

map_view::map_view(const context& ctx, std::vector<field> layers)
    : ctx_(&ctx), layers_(std::move(layers)), anchor_(layers_.front().node) {
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const field& layer = layers_[i];
    if (i > 0 && !layer.node.IsDefined()) continue;
    if (!layer.node.IsMap()) fail_value(ctx, layer, "a map of fields (key: value)");
  }
}

const map_view& map_view::allow(const std::vector<std::string>& keys) const {
  for (const field& layer : layers_) {
    if (!layer.node.IsDefined()) continue;
    std::set<std::string> seen;
    for (const auto& entry : layer.node) {
      const std::string key = key_text(*ctx_, layer, entry.first);
      if (!seen.insert(key).second) ctx_->fail(entry.first, join(layer.path, key), "duplicate key");
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      ctx_->fail(entry.first, join(layer.path, key), "unknown key" + unknown_name_hint(key, keys));
    }
  }
  return *this;
}

bool map_view::has(std::string_view key) const { return get(key).has_value(); }

std::optional<field> map_view::get(std::string_view key) const {
  for (const field& layer : layers_) {
    if (!layer.node.IsDefined()) continue;
    for (const auto& entry : layer.node) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) {
        return field{entry.second, join(layer.path, key), std::string(key)};
      }
    }
  }
  return std::nullopt;
}

field map_view::require(std::string_view key) const {
  if (auto f = get(key)) return *f;
  ctx_->fail(anchor_, self().path.empty() ? std::string(key) : self().path,
             "missing required field " + std::string(key));
}

map_view map_view::child(std::string_view key) const {
  std::vector<field> layers;
  for (const field& layer : layers_) {
    if (!layer.node.IsDefined()) continue;
    for (const auto& entry : layer.node) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) {
        layers.push_back({entry.second, join(layer.path, key), std::string(key)});
      }
    }
  }
  if (layers.empty()) {
    map_view absent(*ctx_, {{YAML::Node(YAML::NodeType::Map), join(self().path, key), std::string(key)}});
    absent.anchor_.reset(anchor_);
    return absent;
  }
  return map_view(*ctx_, std::move(layers));
}

std::optional<field> map_view::one_of(const std::vector<std::string>& keys) const {
  for (const field& layer : layers_) {
    if (!layer.node.IsDefined()) continue;
    std::optional<field> found;
    for (const auto& entry : layer.node) {
      if (!entry.first.IsScalar() || std::find(keys.begin(), keys.end(), entry.first.Scalar()) == keys.end()) continue;
      const field f{entry.second, join(layer.path, entry.first.Scalar()), entry.first.Scalar()};
      if (found) ctx_->fail(entry.first, f.path, "give either " + found->key + " or " + f.key + ", not both");
      found = f;
    }
    if (found) return found;
  }
  return std::nullopt;
}

std::optional<double> map_view::quantity(std::string_view base, units alternatives, range r) const {
  const std::optional<field> found = one_of(keys_of(base, alternatives));
  if (!found) return std::nullopt;
  for (const unit& u : alternatives) {
    if (found->key.size() == base.size() + u.suffix.size() && found->key.ends_with(u.suffix)) {
      return read_number(*ctx_, *found, u.label, r, u.to_si) * u.to_si;
    }
  }
  return std::nullopt;  // unreachable: one_of only returns one of the keys
}

double map_view::quantity_or(std::string_view base, units alternatives, double fallback, range r) const {
  return quantity(base, alternatives, r).value_or(fallback);
}

double map_view::required_quantity(std::string_view base, units alternatives, range r) const {
  if (auto value = quantity(base, alternatives, r)) return *value;
  const std::vector<std::string> keys = keys_of(base, alternatives);
  std::string names;
  for (const std::string& k : keys) names += (names.empty() ? "" : " or ") + k;
  ctx_->fail(anchor_, self().path.empty() ? std::string(base) : self().path, "missing required field " + names);
}

std::vector<std::string> keys_of(std::string_view base, units alternatives) {
  std::vector<std::string> keys;
  for (const unit& u : alternatives) keys.push_back(std::string(base) + std::string(u.suffix));
  return keys;
}

}  // namespace mm::scenario_file::detail
