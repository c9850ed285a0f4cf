// `maneuvermap sweep` through its library: the sweep file format and its errors, the grid order and
// seeds, and a reduced sweep end to end (columns, row count, aggregation recomputed from runs.csv,
// output independent of the number of jobs, a failing run recorded without stopping the others).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/support.hpp"
#include "mm/cli/commands.hpp"
#include "mm/cli/sweep.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/simulation.hpp"

namespace {

using namespace mm::cli;
using mm::cli::testing::read_file;
using mm::cli::testing::temp_dir;
using mm::cli::testing::write_file;
namespace sf = mm::scenario_file;

const std::filesystem::path data_dir = std::filesystem::path(MM_TESTS_CLI_DIR) / "data";

/// A sweep of tests/cli/data/small-crossing.yaml (whose runs take a few hundredths of a second):
/// 2 cells (a_kmh 30 and 40) × 1 policy... as given by `body`, after the common head.
std::string sweep_text(const std::string& body) {
  return "format: maneuvermap-sweep/1\nname: small\nscenario: small-crossing.yaml\n" + body;
}

sweep_spec load_text(const std::string& body) { return load_sweep_text(sweep_text(body), "small.yaml", data_dir); }

std::string one_decimal(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

/// The rows of CSV `text` (quoted fields allowed), the header first.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(cell);
      cell.clear();
    } else if (c == '\n') {
      row.push_back(cell);
      rows.push_back(row);
      row.clear();
      cell.clear();
    } else {
      cell += c;
    }
  }
  return rows;
}

/// A CSV file as maps from column name to value.
struct table {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

table read_table(const std::filesystem::path& file) {
  const auto rows = parse_csv(read_file(file));
  table t;
  t.header = rows.at(0);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r].size(), t.header.size()) << file << " row " << r;
    std::map<std::string, std::string> m;
    for (std::size_t c = 0; c < t.header.size() && c < rows[r].size(); ++c) m[t.header[c]] = rows[r][c];
    t.rows.push_back(std::move(m));
  }
  return t;
}

/// Expects `load_text(body)` to fail with a located message containing every piece.
void expect_error(const std::string& body, int line, const std::vector<std::string>& pieces) {
  try {
    load_text(body);
    ADD_FAILURE() << "no error for:\n" << body;
  } catch (const sf::scenario_error& e) {
    EXPECT_EQ(e.source(), "small.yaml");
    EXPECT_EQ(e.line(), line) << e.what();
    for (const std::string& piece : pieces) EXPECT_NE(std::string(e.what()).find(piece), std::string::npos) << e.what();
  }
}

// --- the file format --------------------------------------------------------------------------

TEST(sweep_file, maps_every_key) {
  const sweep_spec spec = load_text(
      "description: two speeds\nagent: A\nparameters:\n  a_kmh: [30, 40]\n  duration_s: 1.5\n"
      "policies: [const:0.5, adj]\nrepetitions: 3\nseed: 100\nkeep_runs: true\n");
  EXPECT_EQ(spec.name, "small");
  EXPECT_EQ(spec.description, "two speeds");
  EXPECT_EQ(spec.agent, "A");
  ASSERT_EQ(spec.parameters.size(), 2U);
  EXPECT_EQ(spec.parameters[0].name, "a_kmh");
  EXPECT_EQ(spec.parameters[0].values, (std::vector<double>{30, 40}));
  EXPECT_EQ(spec.parameters[1].values, (std::vector<double>{1.5}));  // a single number is a list of one
  ASSERT_EQ(spec.policies.size(), 2U);
  EXPECT_EQ(sf::policy_name(spec.policies[0]), "const:0.5");
  EXPECT_EQ(spec.repetitions, 3U);
  EXPECT_EQ(spec.base_seed, 100U);
  EXPECT_TRUE(spec.keep_runs);
  EXPECT_EQ(spec.scenario_argument, (data_dir / "small-crossing.yaml").lexically_normal().string());
}

TEST(sweep_file, defaults_are_the_scenario_own_policy_and_seed_one_repetition_and_the_first_planning_vehicle) {
  const sweep_spec spec = load_text("");
  EXPECT_TRUE(spec.parameters.empty());
  EXPECT_TRUE(spec.policies.empty());
  EXPECT_EQ(spec.scenario_policy, "adj");
  EXPECT_EQ(spec.base_seed, 7U);  // the scenario's seed
  EXPECT_EQ(spec.repetitions, 1U);
  EXPECT_EQ(spec.agent, "A");
  EXPECT_FALSE(spec.keep_runs);
  const std::vector<sweep_run> runs = expand(spec);
  ASSERT_EQ(runs.size(), 1U);
  EXPECT_EQ(runs[0].policy, "adj");
  EXPECT_EQ(run_command_line(spec, runs[0]), "maneuvermap run " + spec.scenario_argument + " --seed 7");
}

TEST(sweep_file, grid_order_is_parameters_first_outermost_then_policies_then_repetitions) {
  const sweep_spec spec =
      load_text("parameters:\n  a_kmh: [40, 30]\n  b_kmh: [20, 25]\npolicies: [adj, const:1.0]\nrepetitions: 2\nseed: 5\n");
  const std::vector<sweep_run> runs = expand(spec);
  ASSERT_EQ(runs.size(), 16U);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const sweep_run& r = runs[i];
    EXPECT_EQ(r.index, i);
    EXPECT_EQ(r.values[0], i < 8 ? 40.0 : 30.0);
    EXPECT_EQ(r.values[1], (i / 4) % 2 == 0 ? 20.0 : 25.0);
    EXPECT_EQ(r.policy, (i / 2) % 2 == 0 ? "adj" : "const:1");
    EXPECT_EQ(r.repetition, i % 2);
    EXPECT_EQ(r.seed, 5 + i % 2);  // base seed + repetition, the same in every cell
  }
  EXPECT_EQ(runs[3].run_dir, "a_kmh=40_b_kmh=20_const1_rep1");
  EXPECT_EQ(run_command_line(spec, runs[3]), "maneuvermap run " + spec.scenario_argument +
                                                 " --set a_kmh=40 --set b_kmh=20 --policy const:1 --seed 6");
  sweep_spec on_roads = spec;
  on_roads.on_roads = true;
  EXPECT_EQ(run_command_line(on_roads, runs[3]), run_command_line(spec, runs[3]) + " --on-roads");
}

TEST(sweep_file, built_in_sweeps_load_with_their_grids) {
  const sweep_spec table1 = load_sweep("table1");
  EXPECT_EQ(table1.source, "builtin:table1");
  EXPECT_EQ(table1.scenario_argument, "s3-left-turn");
  ASSERT_EQ(table1.parameters.size(), 2U);
  EXPECT_EQ(table1.parameters[0].name, "a_kmh");
  EXPECT_EQ(table1.parameters[1].name, "b_kmh");
  EXPECT_EQ(table1.policies.size(), 5U);
  EXPECT_EQ(table1.repetitions, 10U);
  const std::vector<sweep_run> runs = expand(table1);
  ASSERT_EQ(runs.size(), 500U);
  // The cells come in the row order of the paper's Table 1 (data/paper/table1.csv).
  const auto paper = parse_csv(read_file(std::filesystem::path(MM_SOURCE_DIR) / "data/paper/table1.csv"));
  ASSERT_EQ(paper.size(), 51U);
  for (std::size_t cell = 0; cell < 50; ++cell) {
    const sweep_run& r = runs[cell * 10];
    EXPECT_EQ(r.values[0], std::stod(paper[cell + 1][0]));
    EXPECT_EQ(r.values[1], std::stod(paper[cell + 1][1]));
    std::string policy = r.policy;
    if (policy.starts_with("const:")) policy = "const_" + one_decimal(std::stod(policy.substr(6)));
    EXPECT_EQ(policy, paper[cell + 1][2]) << cell;
  }
  const sweep_spec roundabout = load_sweep("roundabout");
  EXPECT_EQ(roundabout.scenario_argument, "s2-roundabout");
  EXPECT_TRUE(roundabout.keep_runs);
  EXPECT_EQ(expand(roundabout).size(), 5U);
}

TEST(sweep_file, unknown_duplicate_and_missing_keys_are_located_errors) {
  expect_error("policys: [adj]\n", 4, {"small.yaml:4:1: policys: unknown key; did you mean policies?"});
  expect_error("colour: red\n", 4,
               {"small.yaml:4:1: colour: unknown key; expected one of format, name, description, scenario, agent, "
                "parameters, policies, repetitions, seed, keep_runs"});
  expect_error("seed: 1\nseed: 2\n", 5, {"seed: duplicate key"});
  try {
    load_sweep_text("format: maneuvermap-sweep/1\nname: x\n", "small.yaml", data_dir);
    ADD_FAILURE();
  } catch (const sf::scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find("scenario: missing required field"), std::string::npos) << e.what();
  }
  try {
    load_sweep_text("format: maneuvermap-sweep/2\nname: x\nscenario: s1-crossing\n", "small.yaml", data_dir);
    ADD_FAILURE();
  } catch (const sf::scenario_error& e) {
    EXPECT_NE(std::string(e.what()).find("small.yaml:1:9: format = maneuvermap-sweep/2: expected maneuvermap-sweep/1"),
              std::string::npos)
        << e.what();
  }
  expect_error("parameters: [1, 2\n", 5, {"small.yaml:5:1: malformed YAML"});
}

TEST(sweep_file, parameters_must_be_the_scenario_own_with_distinct_finite_values) {
  expect_error("parameters:\n  a_kmhh: [30]\n", 5,
               {"small.yaml:5:3: parameters.a_kmhh: not a parameter of small-crossing.yaml; did you mean a_kmh?",
                "a_kmh, b_kmh, duration_s"});
  expect_error("parameters:\n  a_kmh: []\n", 5, {"parameters.a_kmh = <a list>: expected a non-empty list of numbers"});
  expect_error("parameters:\n  a_kmh: [30, fast]\n", 5, {"parameters.a_kmh[1] = fast: expected a finite number"});
  expect_error("parameters:\n  a_kmh: [30, .inf]\n", 5, {"parameters.a_kmh[1] = .inf: expected a finite number"});
  expect_error("parameters:\n  a_kmh: [30, 30.0]\n", 5, {"parameters.a_kmh[1] = 30.0: duplicate value"});
  expect_error("parameters: 30\n", 4, {"parameters = 30: expected a map"});
}

TEST(sweep_file, policies_repetitions_seed_agent_and_keep_runs_are_checked) {
  expect_error("policies: [adj, const:fast]\n", 4, {"policies[1] = \"const:fast\": expected adj, const:SECONDS or robust"});
  expect_error("policies: [const:1, const:1.0]\n", 4, {"policies[1] = \"const:1.0\": duplicate policy"});
  expect_error("policies: []\n", 4, {"policies = <a list>: expected a non-empty list"});
  expect_error("repetitions: 0\n", 4, {"repetitions = 0: expected an integer from 1 to 1000000"});
  expect_error("repetitions: 2.5\n", 4, {"repetitions = 2.5"});
  expect_error("seed: -1\n", 4, {"seed = -1: expected an integer from 0"});
  expect_error("agent: B\n", 4, {"agent = B: expected a planning vehicle of small-crossing.yaml (A)"});
  expect_error("keep_runs: yes\n", 4, {"keep_runs = yes: expected true or false"});
  expect_error("parameters:\n  a_kmh: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\nrepetitions: 200000\n", 6, {"at most 1000000 runs"});
}

TEST(sweep_file, the_scenario_must_exist_and_load) {
  try {
    load_sweep_text("format: maneuvermap-sweep/1\nname: x\nscenario: s3-left-trun\n", "small.yaml", data_dir);
    ADD_FAILURE();
  } catch (const sf::scenario_error& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("did you mean s3-left-turn?"), std::string::npos) << e.what();
  }
  // A broken scenario reports its own location.
  const temp_dir dir("sweep_broken_scenario");
  write_file(dir / "broken.yaml", "format: maneuvermap-scenario/1\nname: b\nduration_s: -1\nagents: []\n");
  try {
    load_sweep_text("format: maneuvermap-sweep/1\nname: x\nscenario: broken.yaml\n", "s.yaml", dir.path());
    ADD_FAILURE();
  } catch (const sf::scenario_error& e) {
    EXPECT_NE(e.source().find("broken.yaml"), std::string::npos) << e.what();
  }
  // A sweep file is found relative to the working directory, its scenario relative to the sweep file.
  write_file(dir / "s.yaml", sweep_text(""));
  std::filesystem::copy_file(data_dir / "small-crossing.yaml", dir / "small-crossing.yaml");
  EXPECT_EQ(load_sweep((dir / "s.yaml").string()).scenario_argument, (dir / "small-crossing.yaml").string());
  EXPECT_THROW(load_sweep("no-such-sweep"), sf::scenario_error);
}

// --- running ----------------------------------------------------------------------------------

/// The reduced sweep of the suite: 2 cells × 2 repetitions of a 1.5 s run.
const char* reduced = "parameters:\n  a_kmh: [30, 40]\n  duration_s: 1.5\npolicies: [adj]\nrepetitions: 2\nseed: 3\n";

double cell_number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

TEST(sweep_run, writes_runs_csv_with_one_row_per_run_in_grid_order) {
  const sweep_spec spec = load_text(reduced);
  const temp_dir dir("sweep_rows");
  sweep_settings settings;
  settings.out_dir = dir.path();
  settings.jobs = 2;
  const sweep_outcome outcome = run_sweep(spec, settings);
  EXPECT_EQ(outcome.failed, 0U);
  ASSERT_EQ(outcome.results.size(), 4U);
  for (const char* name : {"runs.csv", "table.csv", "table.md", "sweep.json"}) EXPECT_TRUE(std::filesystem::exists(dir / name));
  EXPECT_FALSE(std::filesystem::exists(dir / "runs"));  // runs are not kept unless asked

  const table runs = read_table(dir / "runs.csv");
  EXPECT_EQ(runs.header, (std::vector<std::string>{"a_kmh", "duration_s", "policy", "rep", "seed", "crash", "min_dist_m",
                                                   "ttc_at_min_s", "speed_kmh", "bypass", "min_speed_kmh", "max_speed_kmh",
                                                   "time_in_brake_s", "time_in_accel_s", "error"}));
  ASSERT_EQ(runs.rows.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& row = runs.rows[i];
    EXPECT_EQ(row.at("a_kmh"), i < 2 ? "30" : "40");
    EXPECT_EQ(row.at("duration_s"), "1.5");
    EXPECT_EQ(row.at("policy"), "adj");
    EXPECT_EQ(row.at("rep"), std::to_string(i % 2));
    EXPECT_EQ(row.at("seed"), std::to_string(3 + i % 2));
    EXPECT_EQ(row.at("error"), "");
    EXPECT_TRUE(row.at("crash") == "0" || row.at("crash") == "1");
    EXPECT_TRUE(row.at("bypass") == "left" || row.at("bypass") == "right" || row.at("bypass") == "none");
    EXPECT_GE(cell_number(row, "max_speed_kmh"), cell_number(row, "min_speed_kmh"));
    // The row is what `maneuvermap run` gives alone with its parameters, policy and seed.
    sf::load_options options;
    options.overrides = {{"a_kmh", i < 2 ? 30.0 : 40.0}, {"duration_s", 1.5}};
    options.policy = sf::parse_policy("adj");
    options.seed = 3 + i % 2;
    const sf::loaded_scenario alone = sf::load((data_dir / "small-crossing.yaml").string(), options);
    mm::sim::simulation sim(alone.scenario);
    mm::sim::run(sim);
    EXPECT_EQ(row.at("min_speed_kmh"), fixed(sim.all_metrics().at(0).min_speed_kmh)) << i;
    EXPECT_EQ(row.at("min_dist_m"), fixed(*sim.all_metrics().at(0).min_dist_m)) << i;
  }
  // The repetitions differ (seeded noise), so the spread is not trivially zero.
  EXPECT_NE(runs.rows[0].at("min_dist_m"), runs.rows[1].at("min_dist_m"));
}

TEST(sweep_run, table_csv_aggregates_each_cell_as_recomputed_from_runs_csv) {
  const sweep_spec spec = load_text(reduced);
  const temp_dir dir("sweep_table");
  sweep_settings settings;
  settings.out_dir = dir.path();
  settings.jobs = 2;
  run_sweep(spec, settings);
  const table runs = read_table(dir / "runs.csv");
  const table cells = read_table(dir / "table.csv");
  ASSERT_EQ(cells.rows.size(), 2U);
  for (const char* column : {"a_kmh", "duration_s", "policy", "runs", "failed", "crashes", "min_dist_m_mean", "min_dist_m_sd",
                             "ttc_at_min_s_mean", "ttc_at_min_s_sd", "ttc_at_min_s_n", "speed_kmh_mean", "speed_kmh_sd",
                             "min_speed_kmh_mean", "min_speed_kmh_sd", "max_speed_kmh_mean", "max_speed_kmh_sd",
                             "time_in_brake_s_mean", "time_in_brake_s_sd", "time_in_accel_s_mean", "time_in_accel_s_sd",
                             "bypass", "bypass_left", "bypass_right", "bypass_none"}) {
    EXPECT_NE(std::find(cells.header.begin(), cells.header.end(), column), cells.header.end()) << column;
  }
  for (std::size_t c = 0; c < 2; ++c) {
    const auto& cell = cells.rows[c];
    std::vector<std::map<std::string, std::string>> mine;
    for (const auto& r : runs.rows) {
      if (r.at("a_kmh") == cell.at("a_kmh") && r.at("policy") == cell.at("policy")) mine.push_back(r);
    }
    ASSERT_EQ(mine.size(), 2U);
    EXPECT_EQ(cell.at("runs"), "2");
    EXPECT_EQ(cell.at("failed"), "0");
    int crashes = 0;
    std::map<std::string, int> sides;
    for (const auto& r : mine) {
      crashes += r.at("crash") == "1" ? 1 : 0;
      ++sides[r.at("bypass")];
    }
    EXPECT_EQ(cell.at("crashes"), std::to_string(crashes));
    EXPECT_EQ(cell.at("bypass_left"), std::to_string(sides["left"]));
    EXPECT_EQ(cell.at("bypass_right"), std::to_string(sides["right"]));
    EXPECT_EQ(cell.at("bypass_none"), std::to_string(sides["none"]));
    std::string majority = "mixed";
    for (const auto& [side, count] : sides) {
      if (count == 2) majority = side;
    }
    EXPECT_EQ(cell.at("bypass"), majority);
    for (const std::string metric : {"min_dist_m", "speed_kmh", "min_speed_kmh", "max_speed_kmh", "time_in_brake_s",
                                     "time_in_accel_s", "ttc_at_min_s"}) {
      std::vector<double> values;
      for (const auto& r : mine) {
        if (!r.at(metric).empty()) values.push_back(std::stod(r.at(metric)));
      }
      if (metric == "ttc_at_min_s") {
        EXPECT_EQ(cell.at("ttc_at_min_s_n"), std::to_string(values.size()));
      }
      if (values.empty()) {
        EXPECT_EQ(cell.at(metric + "_mean"), "") << metric;
        continue;
      }
      double mean = 0.0;
      for (double v : values) mean += v / static_cast<double>(values.size());
      EXPECT_NEAR(cell_number(cell, metric + "_mean"), mean, 2e-6) << metric;
      if (values.size() < 2) {
        EXPECT_EQ(cell.at(metric + "_sd"), "") << metric;
        continue;
      }
      double squares = 0.0;
      for (double v : values) squares += (v - mean) * (v - mean);
      EXPECT_NEAR(cell_number(cell, metric + "_sd"), std::sqrt(squares / static_cast<double>(values.size() - 1)), 2e-6)
          << metric;
    }
  }
  const std::string md = read_file(dir / "table.md");
  EXPECT_NE(md.find("| a_kmh | duration_s | policy | crashes | min_dist_m |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 30 | 1.5 | adj | "), std::string::npos) << md;
  EXPECT_NE(md.find("| 40 | 1.5 | adj | "), std::string::npos) << md;
}

TEST(sweep_run, files_are_byte_identical_whatever_the_number_of_jobs) {
  sweep_spec spec = load_text(reduced);
  spec.keep_runs = true;
  const temp_dir one("sweep_jobs1");
  const temp_dir two("sweep_jobs2");
  sweep_settings settings;
  settings.out_dir = one.path();
  settings.jobs = 1;
  run_sweep(spec, settings);
  settings.out_dir = two.path();
  settings.jobs = 2;
  run_sweep(spec, settings);
  for (const char* name : {"runs.csv", "table.csv", "table.md", "sweep.json"}) {
    EXPECT_EQ(read_file(one / name), read_file(two / name)) << name;
    EXPECT_FALSE(read_file(one / name).empty()) << name;
  }
  // The kept runs are whole run directories, the same too.
  const nlohmann::json sweep = nlohmann::json::parse(read_file(one / "sweep.json"));
  ASSERT_EQ(sweep["run_dirs"].size(), 4U);
  for (const auto& run_dir : sweep["run_dirs"]) {
    for (const char* name : {"trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"}) {
      const std::filesystem::path file = std::filesystem::path(run_dir.get<std::string>()) / name;
      EXPECT_TRUE(std::filesystem::exists(one.path() / file)) << file;
      EXPECT_EQ(read_file(one.path() / file), read_file(two.path() / file)) << file;
    }
  }
  EXPECT_EQ(sweep["runs"], 4);
  EXPECT_EQ(sweep["scenario"], spec.scenario_argument);
}

TEST(sweep_run, a_failing_run_is_recorded_with_its_error_and_the_others_still_run) {
  // a_kmh = -5 makes the scenario invalid (a negative desired speed): that run fails alone.
  const sweep_spec spec = load_text("parameters:\n  a_kmh: [-5, 30]\n  duration_s: 1\nrepetitions: 2\n");
  const temp_dir dir("sweep_failing");
  sweep_settings settings;
  settings.out_dir = dir.path();
  const sweep_outcome outcome = run_sweep(spec, settings);
  EXPECT_EQ(outcome.failed, 2U);
  const table runs = read_table(dir / "runs.csv");
  ASSERT_EQ(runs.rows.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    if (i < 2) {
      EXPECT_NE(runs.rows[i].at("error").find("desired_speed_kmh"), std::string::npos) << runs.rows[i].at("error");
      EXPECT_EQ(runs.rows[i].at("crash"), "");
      EXPECT_EQ(runs.rows[i].at("min_dist_m"), "");
    } else {
      EXPECT_EQ(runs.rows[i].at("error"), "");
      EXPECT_FALSE(runs.rows[i].at("min_speed_kmh").empty());
    }
  }
  const table cells = read_table(dir / "table.csv");
  ASSERT_EQ(cells.rows.size(), 2U);
  EXPECT_EQ(cells.rows[0].at("failed"), "2");
  EXPECT_EQ(cells.rows[0].at("min_dist_m_mean"), "");
  EXPECT_EQ(cells.rows[0].at("bypass"), "");
  EXPECT_EQ(cells.rows[1].at("failed"), "0");
  EXPECT_NE(read_file(dir / "table.md").find("| failed |"), std::string::npos);
}

}  // namespace
