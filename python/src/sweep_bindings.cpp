// Bindings of the parameter sweeps (`maneuvermap sweep`, docs/outputs.md "Sweeps"): run a sweep file
// or a built-in sweep on every core, write its files, and get its runs back as arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "fields.hpp"
#include "mm/cli/sweep.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/sim/metrics.hpp"

namespace mm::python {

namespace {

/// What a sweep gave: a row per run in grid order, as runs.csv has them.
struct sweep_record {
  std::string name;                          ///< the sweep's name
  std::string agent;                         ///< the planning vehicle whose metrics are reported
  std::vector<std::string> parameters;       ///< the swept parameters, outermost first
  std::vector<double> values;                ///< runs × parameters, row-major
  std::vector<std::string> policy;           ///< per run: `adj`, `const:0.5`, `robust`
  std::vector<std::uint64_t> repetition;     ///< per run
  std::vector<std::uint64_t> seed;           ///< per run
  std::vector<std::optional<sim::run_metrics>> metrics;  ///< per run; None when it failed
  std::vector<std::string> error;            ///< per run; "" when it did not fail
  std::string table;                         ///< table.md: per cell, mean ± sd
  std::vector<std::string> files;            ///< the files written
};

sweep_record record_of(const cli::sweep_spec& spec, const cli::sweep_outcome& outcome) {
  sweep_record r;
  r.name = spec.name;
  r.agent = spec.agent;
  for (const cli::sweep_parameter& p : spec.parameters) r.parameters.push_back(p.name);
  for (const cli::sweep_result& each : outcome.results) {
    r.values.insert(r.values.end(), each.run.values.begin(), each.run.values.end());
    r.policy.push_back(each.run.policy);
    r.repetition.push_back(each.run.repetition);
    r.seed.push_back(each.run.seed);
    r.metrics.push_back(each.metrics);
    r.error.push_back(each.error);
  }
  r.table = cli::table_markdown(spec, outcome.results);
  r.files = outcome.files;
  return r;
}

}  // namespace

void bind_sweeps(py::module_& m) {
  py::class_<sweep_record> record(m, "sweep_record",
                                  "The runs of a sweep in grid order (parameters, then policies, then repetitions), "
                                  "as runs.csv has them.");
  pickled_by_members(record, &sweep_record::name, &sweep_record::agent, &sweep_record::parameters,
                     &sweep_record::values, &sweep_record::policy, &sweep_record::repetition, &sweep_record::seed,
                     &sweep_record::metrics, &sweep_record::error, &sweep_record::table, &sweep_record::files);
  record.def_readonly("name", &sweep_record::name)
      .def_readonly("agent", &sweep_record::agent, "the planning vehicle whose metrics are reported")
      .def_readonly("parameters", &sweep_record::parameters, "the swept parameters, outermost first")
      .def_property_readonly(
          "values",
          [](const sweep_record& r) {
            const auto rows = static_cast<py::ssize_t>(r.policy.size());
            const auto columns = static_cast<py::ssize_t>(r.parameters.size());
            py::array_t<double> out(std::vector<py::ssize_t>{rows, columns});
            double* data = out.mutable_data();
            for (std::size_t i = 0; i < r.values.size(); ++i) data[i] = r.values[i];
            return out;
          },
          "the parameters' values of each run, shape (runs, parameters)")
      .def_readonly("policy", &sweep_record::policy, "each run's forecast policy: adj, const:SECONDS or robust")
      .def_property_readonly("repetition", [](const sweep_record& r) { return array_of(r.repetition); },
                             "each run's repetition, from 0")
      .def_property_readonly("seed", [](const sweep_record& r) { return array_of(r.seed); }, "each run's seed")
      .def_readonly("metrics", &sweep_record::metrics, "each run's metrics of the agent (spec §12); None when it failed")
      .def_readonly("error", &sweep_record::error, "why each run failed; empty when it did not")
      .def_property_readonly("failed", [](const sweep_record& r) {
        std::size_t failed = 0;
        for (const std::string& e : r.error) failed += e.empty() ? 0 : 1;
        return failed;
      }, "how many runs failed")
      .def_readonly("table", &sweep_record::table, "table.md: per cell (parameters × policy), mean ± sd")
      .def_readonly("files", &sweep_record::files, "the files written")
      .def("__len__", [](const sweep_record& r) { return r.policy.size(); })
      .def("__repr__", [](const sweep_record& r) {
        std::size_t failed = 0;
        for (const std::string& e : r.error) failed += e.empty() ? 0 : 1;
        return "sweep_record(" + py::repr(py::str(r.name)).cast<std::string>() + ", " + std::to_string(r.policy.size()) +
               " runs, " + std::to_string(failed) + " failed)";
      });

  m.def("builtin_sweeps", [] {
    std::vector<std::string> names;
    for (const cli::builtin_sweep& b : cli::builtin_sweeps()) names.emplace_back(b.name);
    return names;
  }, "The names of the built-in sweeps (`maneuvermap list`).");

  m.def("write_sweep",
        [](const py::object& sweep, const std::filesystem::path& out_dir, unsigned jobs,
           std::optional<std::size_t> repetitions, bool on_roads, bool keep_runs) {
          const std::string name = py::str(py::module_::import("os").attr("fspath")(sweep));
          cli::sweep_spec spec = cli::load_sweep(name);
          if (repetitions) cli::set_repetitions(spec, *repetitions);  // std::invalid_argument: ValueError
          if (on_roads) {
            scenario_file::load_options check;  // once, before any run, as the command line does
            check.on_roads = true;
            (void)scenario_file::load_text(spec.scenario_text, spec.scenario_source, check);
            spec.on_roads = true;
          }
          if (keep_runs) spec.keep_runs = true;  // else the file's own
          cli::sweep_settings settings;
          settings.out_dir = out_dir;
          settings.jobs = jobs;
          const py::gil_scoped_release release;
          return record_of(spec, cli::run_sweep(spec, settings));
        },
        py::arg("sweep"), py::arg("out_dir"), py::kw_only(), py::arg("jobs") = 0, py::arg("repetitions") = py::none(),
        py::arg("on_roads") = false, py::arg("keep_runs") = false,
        "Runs a built-in sweep (builtin_sweeps()) or a sweep file (docs/outputs.md, \"Sweeps\") as `maneuvermap "
        "sweep` does, on `jobs` threads (0: every core; the results do not depend on it), writes its files "
        "(runs.csv, table.csv, table.md, sweep.json; with keep_runs each run's own) to out_dir and returns its runs. "
        "`repetitions` replaces the file's; keep_runs=True keeps the runs of a file that does not. A failed run is "
        "recorded with its error. Releases the GIL.");
}

}  // namespace mm::python
