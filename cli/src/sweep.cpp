#include "mm/cli/sweep.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "output_files.hpp"
#include "mm/cli/commands.hpp"
#include "mm/scenario_file/builtin.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::cli {
namespace generated {
extern const builtin_sweep table[];
extern const std::size_t table_size;
}  // namespace generated

std::span<const builtin_sweep> builtin_sweeps() { return {generated::table, generated::table_size}; }

const builtin_sweep* find_builtin_sweep(std::string_view name) {
  for (const builtin_sweep& b : builtin_sweeps()) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

namespace {

using output::csv_field;
using output::write_text;

namespace sf = mm::scenario_file;

constexpr std::size_t max_runs = largest_run_count;

const std::vector<std::string> sweep_keys{"format",   "name", "description", "scenario",    "agent",
                                          "parameters", "policies", "repetitions", "seed", "keep_runs"};

/// "; did you mean X?" when `word` is a plausible typo of one of `candidates`.
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string best = sf::closest_name(word, candidates);
  return best.empty() ? std::string() : "; did you mean " + best + "?";
}

/// Where a sweep file is being read, for located errors like the scenario loader's.
struct reader {
  std::string source;

  [[noreturn]] void fail(const YAML::Node& where, const std::string& field, const std::string& problem) const {
    int line = 0;
    int column = 0;
    if (where.IsDefined() && where.Mark().line >= 0) {
      line = where.Mark().line + 1;
      column = where.Mark().column + 1;
    }
    throw sf::scenario_error(source, line, column, field, problem);
  }

  static std::string shown(const YAML::Node& node) {
    if (!node.IsDefined() || node.IsNull()) return "<nothing>";
    if (node.IsMap()) return "<a map>";
    if (node.IsSequence()) return "<a list>";
    std::string out = node.Scalar().size() > 60 ? node.Scalar().substr(0, 57) + "..." : node.Scalar();
    const bool quote = out.empty() || out.find_first_of(" :,#") != std::string::npos;
    return quote ? "\"" + out + "\"" : out;
  }

  [[noreturn]] void fail_value(const YAML::Node& node, const std::string& field, const std::string& expected) const {
    fail(node, field, "= " + shown(node) + ": expected " + expected);
  }

  std::string text(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) fail_value(node, field, "a text");
    return node.Scalar();
  }

  double number(const YAML::Node& node, const std::string& field) const {
    if (node.IsScalar()) {
      const std::string& t = node.Scalar();
      double value = 0.0;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
      if (!t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(value)) return value;
    }
    fail_value(node, field, "a finite number");
  }

  std::uint64_t integer(const YAML::Node& node, const std::string& field, std::uint64_t min, std::uint64_t max) const {
    const std::string expected = "an integer from " + std::to_string(min) + " to " + std::to_string(max);
    if (!node.IsScalar()) fail_value(node, field, expected);
    const std::string& t = node.Scalar();
    std::uint64_t value = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || value < min || value > max) {
      fail_value(node, field, expected);
    }
    return value;
  }

  bool boolean(const YAML::Node& node, const std::string& field) const {
    if (node.IsScalar() && (node.Scalar() == "true" || node.Scalar() == "false")) return node.Scalar() == "true";
    fail_value(node, field, "true or false");
  }

  /// The entries of a map, checked for non-scalar and duplicate keys, and (when `allowed` is not
  /// empty) for unknown keys.
  std::vector<std::pair<YAML::Node, YAML::Node>> entries(const YAML::Node& map, const std::string& field,
                                                         const std::vector<std::string>& allowed) const {
    std::vector<std::pair<YAML::Node, YAML::Node>> out;
    std::set<std::string> seen;
    for (const auto& entry : map) {
      const YAML::Node key = entry.first;
      if (!key.IsScalar()) fail(key, field, "expected a key name, found " + shown(key));
      const std::string name = key.Scalar();
      const std::string path = field.empty() ? name : field + "." + name;
      if (!seen.insert(name).second) fail(key, path, "duplicate key");
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        fail(key, path, "unknown key" + sf::unknown_key_hint(name, allowed));
      }
      out.emplace_back(key, entry.second);
    }
    return out;
  }
};

std::string number_text(double value) { return fmt::format("{}", value); }

bool looks_like_path(const std::string& arg) {
  const auto ends_with = [&](std::string_view suffix) {
    return arg.size() >= suffix.size() && arg.compare(arg.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return arg.find('/') != std::string::npos || ends_with(".yaml") || ends_with(".yml");
}

std::optional<std::string> read_whole_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return text.str();
}

std::string policy_slug(const std::string& policy) {
  std::string out;
  for (char c : policy) {
    if (c != ':') out += c;
  }
  return out;
}

std::string shell_word(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.:/=+,") ==
                           std::string::npos) {
    return word;
  }
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

sweep_result run_one(const sweep_spec& spec, const sweep_run& run, const std::filesystem::path& runs_dir) {
  sweep_result result;
  result.run = run;
  try {
    sf::load_options options;
    for (std::size_t p = 0; p < spec.parameters.size(); ++p) options.overrides.emplace_back(spec.parameters[p].name, run.values[p]);
    if (!spec.policies.empty()) options.policy = spec.policies[run.policy_index];
    options.seed = run.seed;
    options.on_roads = spec.on_roads;
    const sf::loaded_scenario loaded = sf::load_text(spec.scenario_text, spec.scenario_source, options);
    std::vector<mm::sim::run_metrics> metrics;
    if (spec.keep_runs) {
      run_settings settings;
      settings.out_dir = runs_dir / run.run_dir;
      metrics = run_scenario(loaded, settings).metrics;
    } else {
      // Nobody reads this run's maps or indices: the planner computes only what the commands need
      // (the same commands, so the same metrics, bit for bit).
      mm::sim::run_options run_options;
      run_options.map_columns = false;
      run_options.decision_only = true;
      mm::sim::simulation sim(loaded.scenario, run_options);
      mm::sim::run(sim);
      metrics = sim.all_metrics();
    }
    for (mm::sim::run_metrics& m : metrics) {
      if (m.agent == spec.agent) result.metrics = std::move(m);
    }
    if (!result.metrics) result.error = "no planning vehicle " + spec.agent + " in the run";
  } catch (const std::exception& e) {
    result.error = e.what();
  } catch (...) {
    result.error = "unknown error";
  }
  if (!result.error.empty()) result.metrics.reset();
  return result;
}

std::string clock_text(double seconds) {
  const auto s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60) : fmt::format("{}:{:02}", s / 60, s % 60);
}

/// The numeric metrics aggregated per cell, as (column, unit decimals in table.md).
struct numeric_metric {
  const char* name;
  int decimals;
  std::optional<double> (*get)(const mm::sim::run_metrics&);
};

const numeric_metric numeric_metrics[] = {
    {"min_dist_m", 2, [](const mm::sim::run_metrics& m) { return m.min_dist_m; }},
    {"ttc_at_min_s", 3, [](const mm::sim::run_metrics& m) { return m.ttc_at_min_s; }},
    {"speed_kmh", 1, [](const mm::sim::run_metrics& m) { return m.speed_kmh; }},
    {"min_speed_kmh", 1, [](const mm::sim::run_metrics& m) { return std::optional<double>(m.min_speed_kmh); }},
    {"max_speed_kmh", 1, [](const mm::sim::run_metrics& m) { return std::optional<double>(m.max_speed_kmh); }},
    {"time_in_brake_s", 2, [](const mm::sim::run_metrics& m) { return std::optional<double>(m.time_in_brake_s); }},
    {"time_in_accel_s", 2, [](const mm::sim::run_metrics& m) { return std::optional<double>(m.time_in_accel_s); }},
};

struct statistic {
  std::size_t n = 0;
  double mean = 0.0;
  std::optional<double> sd;  ///< sample standard deviation (n − 1); none for fewer than two values
};

/// The value as runs.csv writes it (6 decimals), so that the aggregates can be recomputed from it.
std::optional<double> as_written(const std::optional<double>& value) {
  if (!value || !std::isfinite(*value)) return std::nullopt;
  return std::stod(fixed(*value));
}

statistic describe(const std::vector<double>& values) {
  statistic s;
  s.n = values.size();
  if (s.n == 0) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(s.n);
  if (s.n >= 2) {
    double squares = 0.0;
    for (double v : values) squares += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(squares / static_cast<double>(s.n - 1));
  }
  return s;
}

/// One cell of the grid (parameters × policy): its repetitions, contiguous in grid order.
struct cell {
  std::span<const sweep_result> runs;
  std::size_t ok = 0;
  std::size_t failed = 0;
  std::size_t crashes = 0;
  std::size_t left = 0;
  std::size_t right = 0;
  std::size_t none = 0;
  std::vector<statistic> stats;  ///< one per numeric_metrics entry

  /// The side most runs took; `mixed` on a tie for the most; "" without a successful run.
  std::string majority_bypass() const {
    if (ok == 0) return {};
    const std::size_t most = std::max({left, right, none});
    const int tied = (left == most ? 1 : 0) + (right == most ? 1 : 0) + (none == most ? 1 : 0);
    if (tied > 1) return "mixed";
    return left == most ? "left" : right == most ? "right" : "none";
  }
  std::size_t majority_count() const { return std::max({left, right, none}); }
};

std::vector<cell> cells_of(const sweep_spec& spec, std::span<const sweep_result> results) {
  std::vector<cell> cells;
  const std::size_t size = std::max<std::size_t>(1, spec.repetitions);
  for (std::size_t start = 0; start < results.size(); start += size) {
    cell c;
    c.runs = results.subspan(start, std::min(size, results.size() - start));
    std::vector<std::vector<double>> values(std::size(numeric_metrics));
    for (const sweep_result& r : c.runs) {
      if (!r.metrics) {
        ++c.failed;
        continue;
      }
      ++c.ok;
      const mm::sim::run_metrics& m = *r.metrics;
      if (m.crash) ++c.crashes;
      switch (m.bypass) {
        case mm::sim::bypass_side::left: ++c.left; break;
        case mm::sim::bypass_side::right: ++c.right; break;
        case mm::sim::bypass_side::none: ++c.none; break;
      }
      for (std::size_t k = 0; k < std::size(numeric_metrics); ++k) {
        if (const std::optional<double> v = as_written(numeric_metrics[k].get(m))) values[k].push_back(*v);
      }
    }
    for (const std::vector<double>& v : values) c.stats.push_back(describe(v));
    cells.push_back(std::move(c));
  }
  return cells;
}

std::string parameter_cells(const sweep_spec& spec, const sweep_run& run, const char* separator) {
  std::string out;
  for (std::size_t p = 0; p < spec.parameters.size(); ++p) out += number_text(run.values[p]) + separator;
  return out;
}

std::string sweep_json(const sweep_spec& spec, std::span<const sweep_result> results, std::size_t failed) {
  using json = nlohmann::ordered_json;
  json parameters = json::object();
  for (const sweep_parameter& p : spec.parameters) parameters[p.name] = p.values;
  json policies = json::array();
  if (spec.policies.empty()) policies.push_back(spec.scenario_policy);
  for (const mm::forecast_policy& p : spec.policies) policies.push_back(sf::policy_name(p));
  json runs = json::array();
  if (spec.keep_runs) {
    for (const sweep_result& r : results) runs.push_back("runs/" + r.run.run_dir);
  }
  const json doc = {{"format", "maneuvermap-sweep-result/1"},
                    {"sweep", spec.name},
                    {"description", spec.description},
                    {"source", spec.source},
                    {"scenario", spec.scenario_argument},
                    {"agent", spec.agent},
                    {"parameters", parameters},
                    {"policies", policies},
                    {"repetitions", spec.repetitions},
                    {"base_seed", spec.base_seed},
                    {"runs", results.size()},
                    {"failed", failed},
                    {"keep_runs", spec.keep_runs},
                    {"on_roads", spec.on_roads},
                    {"run_dirs", runs}};
  return doc.dump(2) + "\n";
}

}  // namespace

sweep_spec load_sweep_text(std::string_view text, const std::string& source, const std::filesystem::path& base_dir) {
  const reader in{source};
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::DeepRecursion& e) {
    throw sf::scenario_error(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, e.mark.line >= 0 ? e.mark.column + 1 : 0, "",
                             "malformed YAML: nested " + std::to_string(e.depth()) +
                                 " levels deep, deeper than the YAML reader goes (a sweep file nests a few levels)");
  } catch (const YAML::Exception& e) {
    throw sf::scenario_error(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, e.mark.line >= 0 ? e.mark.column + 1 : 0, "",
                             "malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) in.fail_value(root, "", "a map of the keys of a sweep file (format, name, scenario, ...)");
  const auto entries = in.entries(root, "", sweep_keys);
  const auto get = [&](std::string_view key) -> YAML::Node {
    for (const auto& [k, v] : entries) {
      if (k.Scalar() == key) return v;
    }
    return YAML::Node(YAML::NodeType::Undefined);
  };
  const auto require = [&](const std::string& key) {
    YAML::Node node = get(key);
    if (!node.IsDefined()) in.fail(root, key, "missing required field");
    return node;
  };

  sweep_spec spec;
  spec.source = source;
  const YAML::Node format = require("format");
  if (in.text(format, "format") != sweep_format_version) {
    in.fail_value(format, "format", std::string(sweep_format_version) + " (the only version this program reads)");
  }
  const YAML::Node name = require("name");
  spec.name = in.text(name, "name");
  if (spec.name.empty() || spec.name.find('/') != std::string::npos || spec.name == "." || spec.name == "..") {
    in.fail_value(name, "name", "a non-empty name without '/' (it names the output directory out/NAME)");
  }
  if (const YAML::Node d = get("description"); d.IsDefined()) spec.description = in.text(d, "description");

  // The scenario: a built-in name, or a file relative to the sweep file.
  const YAML::Node scenario = require("scenario");
  spec.scenario = in.text(scenario, "scenario");
  const sf::builtin_scenario* builtin = looks_like_path(spec.scenario) ? nullptr : sf::find_builtin(spec.scenario);
  if (builtin != nullptr) {
    spec.scenario_argument = spec.scenario;
    spec.scenario_source = "builtin:" + spec.scenario;
    spec.scenario_text = std::string(builtin->text);
  } else {
    std::filesystem::path file(spec.scenario);
    if (file.is_relative()) file = base_dir / file;
    file = file.lexically_normal();
    std::optional<std::string> bytes = spec.scenario.empty() ? std::nullopt : read_whole_file(file);
    if (!bytes) {
      std::vector<std::string> names;
      for (const sf::builtin_scenario& b : sf::builtin_scenarios()) names.emplace_back(b.name);
      in.fail_value(scenario, "scenario",
                    "a built-in scenario (`maneuvermap list`) or a readable scenario file; cannot read " + file.string() +
                        suggestion(spec.scenario, names));
    }
    spec.scenario_argument = file.string();
    spec.scenario_source = file.string();
    spec.scenario_text = std::move(*bytes);
  }
  const sf::loaded_scenario loaded = sf::load_text(spec.scenario_text, spec.scenario_source);
  std::vector<std::string> vehicles;
  for (const mm::sim::planning_vehicle& v : loaded.scenario.planning_vehicles) vehicles.push_back(v.name);
  if (vehicles.empty()) in.fail_value(scenario, "scenario", "a scenario with a planning vehicle");

  spec.agent = vehicles.front();
  if (const YAML::Node a = get("agent"); a.IsDefined()) {
    spec.agent = in.text(a, "agent");
    if (std::find(vehicles.begin(), vehicles.end(), spec.agent) == vehicles.end()) {
      std::string list;
      for (const std::string& v : vehicles) list += (list.empty() ? "" : ", ") + v;
      in.fail_value(a, "agent", "a planning vehicle of " + spec.scenario + " (" + list + ")");
    }
  }
  for (const mm::sim::planning_vehicle& v : loaded.scenario.planning_vehicles) {
    if (v.name == spec.agent) spec.scenario_policy = sf::policy_name(v.planner.policy);
  }

  std::size_t runs = 1;
  if (const YAML::Node params = get("parameters"); params.IsDefined()) {
    if (!params.IsMap()) in.fail_value(params, "parameters", "a map from parameter name to a list of values");
    std::vector<std::string> known;
    for (const sf::parameter& p : loaded.parameters) known.push_back(p.name);
    for (const auto& [key, value] : in.entries(params, "parameters", {})) {
      const std::string field = "parameters." + key.Scalar();
      if (std::find(known.begin(), known.end(), key.Scalar()) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        in.fail(key, field,
                "not a parameter of " + spec.scenario + suggestion(key.Scalar(), known) +
                    " (its parameters: " + (list.empty() ? "none" : list) + ")");
      }
      sweep_parameter p;
      p.name = key.Scalar();
      if (value.IsSequence()) {
        if (value.size() == 0) in.fail_value(value, field, "a non-empty list of numbers");
        for (std::size_t i = 0; i < value.size(); ++i) {
          const std::string item = field + "[" + std::to_string(i) + "]";
          const double v = in.number(value[i], item);
          if (std::find(p.values.begin(), p.values.end(), v) != p.values.end()) {
            in.fail(value[i], item, "= " + reader::shown(value[i]) + ": duplicate value");
          }
          p.values.push_back(v);
        }
      } else {
        p.values.push_back(in.number(value, field));
      }
      runs *= p.values.size();
      if (runs > max_runs) in.fail_value(value, field, "at most " + std::to_string(max_runs) + " runs in all");
      spec.parameters.push_back(std::move(p));
    }
  }

  if (const YAML::Node policies = get("policies"); policies.IsDefined()) {
    if (!policies.IsSequence() || policies.size() == 0) {
      in.fail_value(policies, "policies", "a non-empty list of policies: " + std::string(scenario_file::policy_forms));
    }
    std::set<std::string> seen;
    for (std::size_t i = 0; i < policies.size(); ++i) {
      const std::string field = "policies[" + std::to_string(i) + "]";
      const std::optional<mm::forecast_policy> policy = sf::parse_policy(in.text(policies[i], field));
      if (!policy) in.fail_value(policies[i], field, std::string(scenario_file::policy_forms) + ", e.g. const:1.0");
      if (!seen.insert(sf::policy_name(*policy)).second) {
        in.fail(policies[i], field, "= " + reader::shown(policies[i]) + ": duplicate policy");
      }
      spec.policies.push_back(*policy);
    }
    runs *= spec.policies.size();
  }

  if (const YAML::Node r = get("repetitions"); r.IsDefined()) spec.repetitions = in.integer(r, "repetitions", 1, max_runs);
  runs *= spec.repetitions;
  if (runs > max_runs) in.fail_value(get("repetitions"), "repetitions", "at most " + std::to_string(max_runs) + " runs in all");

  spec.base_seed = loaded.scenario.seed;
  if (const YAML::Node s = get("seed"); s.IsDefined()) {
    spec.base_seed = in.integer(s, "seed", 0, std::numeric_limits<std::uint64_t>::max() - max_runs);
  }
  if (const YAML::Node k = get("keep_runs"); k.IsDefined()) spec.keep_runs = in.boolean(k, "keep_runs");
  return spec;
}

sweep_spec load_sweep(std::string_view file_or_builtin) {
  const std::string arg(file_or_builtin);
  if (!looks_like_path(arg)) {
    if (const builtin_sweep* b = find_builtin_sweep(arg)) return load_sweep_text(b->text, "builtin:" + arg, ".");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(arg, ec)) {
      std::vector<std::string> names;
      for (const builtin_sweep& b : builtin_sweeps()) names.emplace_back(b.name);
      throw sf::scenario_error(arg, 0, 0, "",
                               "no such file or built-in sweep" + suggestion(arg, names) +
                                   " (`maneuvermap list` shows the built-in sweeps)");
    }
  }
  std::error_code error;
  if (std::filesystem::is_directory(arg, error)) throw sf::scenario_error(arg, 0, 0, "", "is a directory; expected a sweep file (YAML)");
  const std::optional<std::string> text = read_whole_file(arg);
  if (!text) throw sf::scenario_error(arg, 0, 0, "", std::string("cannot read the file: ") + std::strerror(errno));
  return load_sweep_text(*text, arg, std::filesystem::path(arg).parent_path());
}

void set_repetitions(sweep_spec& spec, std::size_t repetitions) {
  std::size_t cells = std::max<std::size_t>(1, spec.policies.size());
  for (const sweep_parameter& p : spec.parameters) cells *= p.values.size();
  if (repetitions == 0 || repetitions > largest_run_count / cells) {
    throw std::invalid_argument("repetitions = " + std::to_string(repetitions) + ": expected from 1 to " +
                                std::to_string(largest_run_count / cells) + " (" + std::to_string(cells) +
                                " cells; at most " + std::to_string(largest_run_count) + " runs in all)");
  }
  spec.repetitions = repetitions;
}

std::vector<sweep_run> expand(const sweep_spec& spec) {
  std::vector<sweep_run> runs;
  std::vector<std::size_t> at(spec.parameters.size(), 0);  // an odometer over the parameter values
  const std::size_t policies = std::max<std::size_t>(1, spec.policies.size());
  while (true) {
    for (std::size_t k = 0; k < policies; ++k) {
      for (std::size_t r = 0; r < spec.repetitions; ++r) {
        sweep_run run;
        run.index = runs.size();
        std::string dir;
        for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
          run.values.push_back(spec.parameters[p].values[at[p]]);
          dir += spec.parameters[p].name + "=" + number_text(run.values.back()) + "_";
        }
        run.policy_index = k;
        run.policy = spec.policies.empty() ? spec.scenario_policy : sf::policy_name(spec.policies[k]);
        run.repetition = r;
        run.seed = spec.base_seed + r;
        run.run_dir = dir + policy_slug(run.policy) + "_rep" + std::to_string(r);
        runs.push_back(std::move(run));
      }
    }
    std::size_t p = spec.parameters.size();
    while (p > 0 && ++at[p - 1] == spec.parameters[p - 1].values.size()) at[--p] = 0;
    if (p == 0) break;
  }
  return runs;
}

std::string run_command_line(const sweep_spec& spec, const sweep_run& run) {
  std::string out = "maneuvermap run " + shell_word(spec.scenario_argument);
  for (std::size_t p = 0; p < spec.parameters.size(); ++p) {
    out += " --set " + spec.parameters[p].name + "=" + number_text(run.values[p]);
  }
  if (!spec.policies.empty()) out += " --policy " + run.policy;
  out += " --seed " + std::to_string(run.seed);
  if (spec.on_roads) out += " --on-roads";
  return out;
}

sweep_outcome run_sweep(const sweep_spec& spec, const sweep_settings& settings) {
  const std::vector<sweep_run> runs = expand(spec);
  std::filesystem::create_directories(settings.out_dir);
  const std::filesystem::path runs_dir = settings.out_dir / "runs";
  if (spec.keep_runs) std::filesystem::create_directories(runs_dir);

  unsigned jobs = settings.jobs != 0 ? settings.jobs : std::max(1U, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, std::max<std::size_t>(1, runs.size())));

  std::vector<sweep_result> results(runs.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;
  std::size_t failed_so_far = 0;
  const auto started = std::chrono::steady_clock::now();
  auto last_drawn = started - std::chrono::seconds(1);
  const auto draw = [&](bool force) {  // under progress_mutex
    if (settings.progress == nullptr) return;
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_drawn < std::chrono::milliseconds(200)) return;
    last_drawn = now;
    const double elapsed = std::chrono::duration<double>(now - started).count();
    constexpr std::size_t width = 30;
    const std::size_t filled = runs.empty() ? width : width * done / runs.size();
    std::string line = fmt::format("\r{} [{}{}] {}/{} runs", spec.name, std::string(filled, '#'),
                                   std::string(width - filled, '.'), done, runs.size());
    if (failed_so_far > 0) line += fmt::format(", {} failed", failed_so_far);
    line += ", " + clock_text(elapsed);
    if (done > 0 && done < runs.size()) {
      line += ", ~" + clock_text(elapsed / static_cast<double>(done) * static_cast<double>(runs.size() - done)) + " left";
    }
    *settings.progress << line << "\033[K" << std::flush;
  };
  const auto work = [&] {
    while (true) {
      const std::size_t i = next.fetch_add(1);
      if (i >= runs.size()) return;
      results[i] = run_one(spec, runs[i], runs_dir);
      const std::lock_guard lock(progress_mutex);
      ++done;
      if (!results[i].error.empty()) ++failed_so_far;
      draw(false);
    }
  };
  {
    const std::lock_guard lock(progress_mutex);
    draw(true);
  }
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < jobs; ++j) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (settings.progress != nullptr) *settings.progress << "\r\033[K" << std::flush;

  sweep_outcome outcome;
  for (const sweep_result& r : results) outcome.failed += r.error.empty() ? 0 : 1;
  const auto write = [&](const char* name, const std::string& text) {
    write_text(settings.out_dir / name, text);
    outcome.files.push_back((settings.out_dir / name).string());
  };
  write("runs.csv", runs_csv(spec, results));
  write("table.csv", table_csv(spec, results));
  write("table.md", table_markdown(spec, results));
  write("sweep.json", sweep_json(spec, results, outcome.failed));
  outcome.results = std::move(results);
  return outcome;
}

std::string runs_csv(const sweep_spec& spec, std::span<const sweep_result> results) {
  std::string out;
  for (const sweep_parameter& p : spec.parameters) out += p.name + ",";
  out += "policy,rep,seed,crash,min_dist_m,ttc_at_min_s,speed_kmh,bypass,min_speed_kmh,max_speed_kmh,time_in_brake_s,"
         "time_in_accel_s,error\n";
  const auto opt = [](const std::optional<double>& v) { return v ? fixed(*v) : std::string(); };
  for (const sweep_result& r : results) {
    out += parameter_cells(spec, r.run, ",");
    out += fmt::format("{},{},{},", r.run.policy, r.run.repetition, r.run.seed);
    if (r.metrics) {
      const mm::sim::run_metrics& m = *r.metrics;
      out += fmt::format("{},{},{},{},{},{},{},{},{},", m.crash ? 1 : 0, opt(m.min_dist_m), opt(m.ttc_at_min_s),
                         opt(m.speed_kmh), mm::sim::to_string(m.bypass), fixed(m.min_speed_kmh), fixed(m.max_speed_kmh),
                         fixed(m.time_in_brake_s), fixed(m.time_in_accel_s));
    } else {
      out += ",,,,,,,,,";
    }
    out += csv_field(r.error) + "\n";
  }
  return out;
}

std::string table_csv(const sweep_spec& spec, std::span<const sweep_result> results) {
  std::string out;
  for (const sweep_parameter& p : spec.parameters) out += p.name + ",";
  out += "policy,runs,failed,crashes";
  for (const numeric_metric& m : numeric_metrics) {
    out += fmt::format(",{0}_mean,{0}_sd", m.name);
    if (std::string_view(m.name) == "ttc_at_min_s") out += ",ttc_at_min_s_n";
  }
  out += ",bypass,bypass_left,bypass_right,bypass_none\n";
  for (const cell& c : cells_of(spec, results)) {
    const sweep_run& first = c.runs.front().run;
    out += parameter_cells(spec, first, ",");
    out += fmt::format("{},{},{},{}", first.policy, c.runs.size(), c.failed, c.crashes);
    for (std::size_t k = 0; k < std::size(numeric_metrics); ++k) {
      const statistic& s = c.stats[k];
      out += fmt::format(",{},{}", s.n > 0 ? fixed(s.mean) : std::string(), s.sd ? fixed(*s.sd) : std::string());
      if (std::string_view(numeric_metrics[k].name) == "ttc_at_min_s") out += fmt::format(",{}", s.n);
    }
    out += fmt::format(",{},{},{},{}\n", c.majority_bypass(), c.left, c.right, c.none);
  }
  return out;
}

std::string table_markdown(const sweep_spec& spec, std::span<const sweep_result> results) {
  const std::vector<cell> cells = cells_of(spec, results);
  std::size_t failed = 0;
  for (const cell& c : cells) failed += c.failed;
  std::string out = fmt::format("# Sweep `{}`\n\n", spec.name);
  if (!spec.description.empty()) out += spec.description + "\n\n";
  const std::string seeds = spec.repetitions == 1
                                ? fmt::format("1 run per cell, seed {}", spec.base_seed)
                                : fmt::format("{} repetitions per cell, seeds {} to {} (seed = {} + repetition)",
                                              spec.repetitions, spec.base_seed, spec.base_seed + spec.repetitions - 1,
                                              spec.base_seed);
  out += fmt::format("Scenario `{}`, metrics of {}; {} run{} ({} failed); {}.\n\n", spec.scenario_argument, spec.agent,
                     results.size(), results.size() == 1 ? "" : "s", failed, seeds);
  out += "Each cell: mean ± sample standard deviation over its runs (a count in brackets when fewer runs had a "
         "value); crashes: runs that crashed / runs; bypass: the majority side (runs on it / runs).\n\n";
  std::vector<std::string> header;
  for (const sweep_parameter& p : spec.parameters) header.push_back(p.name);
  header.insert(header.end(), {"policy", "crashes", "min_dist_m", "ttc_at_min_s", "speed_kmh", "bypass", "min_speed_kmh",
                               "max_speed_kmh"});
  if (failed > 0) header.emplace_back("failed");
  out += "|";
  for (const std::string& h : header) out += " " + h + " |";
  out += "\n|";
  for (std::size_t h = 0; h < header.size(); ++h) {
    const bool text = header[h] == "policy" || header[h] == "bypass";
    out += text ? ":---|" : "---:|";
  }
  out += "\n";
  const auto shown = [](const statistic& s, int decimals, std::size_t ok) {
    if (s.n == 0) return std::string("–");
    std::string text = fixed(s.mean, decimals);
    if (s.sd) text += " ± " + fixed(*s.sd, decimals);
    if (s.n < ok) text += fmt::format(" ({})", s.n);
    return text;
  };
  for (const cell& c : cells) {
    const sweep_run& first = c.runs.front().run;
    out += "| " + parameter_cells(spec, first, " | ") + first.policy + " | ";
    out += fmt::format("{}/{} | ", c.crashes, c.ok);
    for (std::size_t k = 0; k < 3; ++k) out += shown(c.stats[k], numeric_metrics[k].decimals, c.ok) + " | ";
    out += c.ok == 0 ? std::string("–") : fmt::format("{} {}/{}", c.majority_bypass(), c.majority_count(), c.ok);
    out += " | ";
    for (std::size_t k = 3; k < 5; ++k) out += shown(c.stats[k], numeric_metrics[k].decimals, c.ok) + " | ";
    if (failed > 0) out += std::to_string(c.failed) + " |";
    while (out.back() == ' ') out.pop_back();
    out += "\n";
  }
  return out;
}

}  // namespace mm::cli
