// Bindings of the simulator and its scenario files (docs/python.md): load a scenario, run it step by
// step or whole, read every agent's states and every planning vehicle's Maneuverability Map.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl_bind.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "fields.hpp"
#include "scenario_bindings.hpp"
#include "mm/cli/commands.hpp"
#include "mm/scenario_file/builtin.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/scenario_file/writer.hpp"
#include "mm/sim/simulation.hpp"

namespace mm::python {

namespace {

using scenario_file::loaded_scenario;
using sim::agent_id;

/// The Maneuverability Map of one planning vehicle over a run: one row per planning step.
struct map_record {
  std::string agent;
  std::vector<double> times;           ///< when it planned [s]
  std::vector<double> forecast_times;  ///< τ_i [s]
  std::vector<double> mi_brake;        ///< row-major (steps × forecast times)
  std::vector<double> mi_accelerate;
  std::vector<std::uint8_t> excluded;
  std::vector<double> forecast_time;   ///< τ̄ [s]
  std::vector<std::uint8_t> selected_family;
  std::vector<std::uint8_t> mode;
  std::vector<double> time_to_collision;
  std::vector<double> command_acceleration;
  std::vector<double> command_curvature;
  std::vector<double> cpu_time_us;
  std::vector<std::uint8_t> robust;
  std::vector<std::uint8_t> indices_computed;
};

/// Everything a run of `run` recorded: the states of every agent at every step, the maps.
struct run_record {
  std::string scenario;
  std::string source;
  std::vector<sim::agent_info> agents;
  std::vector<double> times;
  std::size_t agent_count = 0;
  // (steps × agents), row-major
  std::vector<double> x, y, heading, speed, acceleration, curvature, arc_length, lateral_offset;
  std::vector<std::uint8_t> status;
  std::vector<map_record> maps;  ///< one per planning vehicle, in id order
  std::vector<sim::run_metrics> metrics;
  std::vector<sim::crash_event> crashes;
};

/// `values`, row-major, as a (rows × `columns`) NumPy array of T (no rows when there are no columns).
template <class T = double, class U>
py::array_t<T> matrix_of(const std::vector<U>& values, std::size_t columns) {
  const auto c = static_cast<py::ssize_t>(columns);
  const auto r = c == 0 ? py::ssize_t{0} : static_cast<py::ssize_t>(values.size()) / c;
  py::array_t<T> out({r, c});
  T* data = out.mutable_data();
  for (std::size_t i = 0; i < static_cast<std::size_t>(r * c); ++i) data[i] = static_cast<T>(values[i]);
  return out;
}

/// One index of a map over its steps: (steps × forecast times), or (steps × 0) when the planner
/// computed no map column.
py::array_t<double> index_matrix(const map_record& r, const std::vector<double>& values) {
  if (values.empty()) {
    return py::array_t<double>(std::vector<py::ssize_t>{static_cast<py::ssize_t>(r.times.size()), 0});
  }
  return matrix_of(values, r.forecast_times.size());
}

void record_instant(const sim::simulation& now, run_record& record) {
  record.times.push_back(now.time());
  for (agent_id id = 0; id < now.agent_count(); ++id) {
    const sim::agent_state& a = now.state(id);
    record.x.push_back(a.pose.position.x);
    record.y.push_back(a.pose.position.y);
    record.heading.push_back(a.pose.heading);
    record.speed.push_back(a.speed);
    record.acceleration.push_back(a.acceleration);
    record.curvature.push_back(a.curvature);
    record.arc_length.push_back(a.arc_length);
    record.lateral_offset.push_back(a.lateral_offset);
    record.status.push_back(static_cast<std::uint8_t>(a.status));
  }
  for (agent_id id = 0; id < now.planning_vehicle_count(); ++id) {
    if (!now.planned_now(id)) continue;
    const sim::plan_record& p = *now.last_plan(id);
    const plan_result& r = p.result;
    map_record& map = record.maps[id];
    if (map.forecast_times.empty()) map.forecast_times = r.forecast_times;
    map.times.push_back(p.time);
    map.mi_brake.insert(map.mi_brake.end(), r.mi_brake.begin(), r.mi_brake.end());
    map.mi_accelerate.insert(map.mi_accelerate.end(), r.mi_accelerate.begin(), r.mi_accelerate.end());
    map.excluded.insert(map.excluded.end(), r.excluded.begin(), r.excluded.end());
    map.forecast_time.push_back(r.forecast_time);
    map.selected_family.push_back(static_cast<std::uint8_t>(r.selected_family));
    map.mode.push_back(static_cast<std::uint8_t>(r.mode));
    map.time_to_collision.push_back(r.time_to_collision);
    map.command_acceleration.push_back(r.command.acceleration);
    map.command_curvature.push_back(r.command.curvature);
    map.cpu_time_us.push_back(p.cpu_time_us);
    map.robust.push_back(r.robust ? 1 : 0);
    map.indices_computed.push_back(r.indices_computed ? 1 : 0);
  }
}

run_record run_whole(const loaded_scenario& loaded, const sim::run_options& options) {
  sim::simulation simulation(loaded.scenario, options);
  run_record record;
  record.scenario = loaded.scenario.name;
  record.source = loaded.source;
  record.agent_count = simulation.agent_count();
  for (agent_id id = 0; id < simulation.agent_count(); ++id) record.agents.push_back(simulation.info(id));
  record.maps.resize(simulation.planning_vehicle_count());
  for (agent_id id = 0; id < simulation.planning_vehicle_count(); ++id) {
    record.maps[id].agent = simulation.info(id).name;
  }
  sim::run(simulation, [&](const sim::simulation& now) { record_instant(now, record); });
  record.metrics = simulation.all_metrics();
  record.crashes.assign(simulation.crashes().begin(), simulation.crashes().end());
  return record;
}

/// A simulation of a copy of `s`, made while the GIL is held; the first decisions are made without it.
/// (A simulation's own steps keep the GIL: other threads may read it between them, never during one.)
std::unique_ptr<sim::simulation> start(const sim::scenario& s, const sim::run_options& options) {
  sim::scenario own = s;
  const py::gil_scoped_release release;
  return std::make_unique<sim::simulation>(std::move(own), options);
}

scenario_file::load_options load_options_of(const std::optional<std::map<std::string, double>>& set,
                                            const std::optional<forecast_policy>& policy,
                                            const std::optional<std::uint64_t>& seed, bool on_roads) {
  scenario_file::load_options options;
  if (set) options.overrides.assign(set->begin(), set->end());
  options.policy = policy;
  options.seed = seed;
  options.on_roads = on_roads;
  return options;
}

/// The scenario `call` (`run`, `write_run`) was given: a built-in name or a file (loaded with the
/// overrides), a loaded_scenario or a scenario (which take none).
loaded_scenario loaded_from(const char* call, const py::object& what, const std::optional<std::map<std::string, double>>& set,
                            const std::optional<forecast_policy>& policy, const std::optional<std::uint64_t>& seed,
                            bool on_roads) {
  const bool is_loaded = py::isinstance<loaded_scenario>(what);
  if ((is_loaded || py::isinstance<sim::scenario>(what)) && (set || policy || seed || on_roads)) {
    throw py::value_error(std::string("set, policy, seed and on_roads apply when loading: pass a name or a file to ") +
                          call + "()");
  }
  if (is_loaded) return what.cast<loaded_scenario>();
  if (py::isinstance<sim::scenario>(what)) {
    loaded_scenario loaded;
    loaded.scenario = what.cast<sim::scenario>();
    loaded.source = "<scenario>";
    return loaded;
  }
  if (py::isinstance<py::str>(what) || py::hasattr(what, "__fspath__")) {
    const std::string name = py::str(py::module_::import("os").attr("fspath")(what));
    return scenario_file::load(name, load_options_of(set, policy, seed, on_roads));
  }
  throw py::type_error(std::string(call) + "(): expected a built-in name, a scenario file, a loaded_scenario or a "
                       "scenario, got " + py::repr(what).cast<std::string>());
}

sim::run_options run_options_of(std::size_t jobs, bool map_columns, bool measure_cpu_time, bool decision_only = false) {
  // As `maneuvermap run --jobs`: at least one thread (the library reads 0 as 1; a caller who wrote 0
  // more likely meant "every core", which it is not).
  if (jobs < 1 || jobs > 256) throw py::value_error("jobs = " + std::to_string(jobs) + ": expected from 1 to 256 threads");
  sim::run_options options;
  options.jobs = jobs;
  options.map_columns = map_columns;
  options.decision_only = decision_only;
  options.measure_cpu_time = measure_cpu_time;
  return options;
}

void bind_scenarios(py::module_& m) {
  static auto* error = new py::exception<scenario_file::scenario_error>(m, "scenario_error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const scenario_file::scenario_error& e) {
      py::object instance = py::reinterpret_borrow<py::object>(error->ptr())(e.what());
      instance.attr("source") = e.source();
      instance.attr("line") = e.line();
      instance.attr("column") = e.column();
      instance.attr("field") = e.field();
      instance.attr("problem") = e.problem();
      PyErr_SetObject(error->ptr(), instance.ptr());
    } catch (const cli::input_error& e) {  // a bad option of the command line's code path
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<scenario_file::parameter>(m, "parameter", "A named number of the file's `parameters:`.")
      .def_readonly("name", &scenario_file::parameter::name)
      .def_readonly("value", &scenario_file::parameter::value, "after overrides")
      .def_readonly("default_value", &scenario_file::parameter::default_value, "as written in the file")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<scenario_file::road>(m, "road", "A road drawn under the agents (not used by the simulation).")
      .def_readonly("name", &scenario_file::road::name)
      .def_property_readonly("centre_line", [](const scenario_file::road& r) { return points_of(r.centre_line); },
                             "[m], shape (points, 2)")
      .def_readonly("width", &scenario_file::road::width, "[m]")
      .def("__repr__", [](const scenario_file::road& r) {
        return "road(name=" + py::repr(py::str(r.name)).cast<std::string>() + ")";
      });
  py::class_<sim::roundabout>(m, "roundabout", "The ring of a roundabout.")
      .def_readonly("center", &sim::roundabout::center, "C [m]")
      .def_readonly("radius", &sim::roundabout::radius, "of the circulating lane's centre line [m]")
      .def_readonly("connection_radius", &sim::roundabout::connection_radius,
                    "of the arcs joining the arms to the ring [m]")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<loaded_scenario> loaded(m, "loaded_scenario", "A scenario file mapped onto the simulator's types.");
  copied_by_value(loaded)
      .def_readwrite("scenario", &loaded_scenario::scenario)
      .def_readonly("roads", &loaded_scenario::roads, "to draw under the agents")
      .def_property_readonly("roundabout", [](const loaded_scenario& s) -> std::optional<sim::roundabout> {
        if (!s.roundabout) return std::nullopt;
        return s.roundabout->ring;
      }, "the ring of the scenario's roundabout, or None")
      .def_readonly("parameters", &loaded_scenario::parameters)
      .def_readonly("source", &loaded_scenario::source, "file name or builtin:NAME")
      .def("__repr__", [](const loaded_scenario& s) {
        return "loaded_scenario(source=" + py::repr(py::str(s.source)).cast<std::string>() + ", name=" +
               py::repr(py::str(s.scenario.name)).cast<std::string>() + ")";
      });

  m.def("builtin_scenarios", [] {
    std::vector<std::string> names;
    for (const auto& b : scenario_file::builtin_scenarios()) names.emplace_back(b.name);
    return names;
  }, "The names of the built-in scenarios.");
  m.def("load",
        [](const py::object& file_or_builtin, const std::optional<std::map<std::string, double>>& set,
           const std::optional<forecast_policy>& policy, const std::optional<std::uint64_t>& seed, bool on_roads) {
          const std::string name = py::str(py::module_::import("os").attr("fspath")(file_or_builtin));
          return scenario_file::load(name, load_options_of(set, policy, seed, on_roads));
        },
        py::arg("file_or_builtin"), py::kw_only(), py::arg("set") = py::none(), py::arg("policy") = py::none(),
        py::arg("seed") = py::none(), py::arg("on_roads") = false,
        "A built-in scenario by name or a scenario file (docs/scenario-format.md), with parameter overrides "
        "(`set={'a_kmh': 20}`), a forecast policy for every planning vehicle, a seed, and `on_roads` (its roads and "
        "roundabout lanes as the drivable area): as `maneuvermap run`. "
        "scenario_error (a ValueError) names the file, line, column and field of any problem.");
  m.def("load_text",
        [](const std::string& text, const std::string& source, const std::optional<std::map<std::string, double>>& set,
           const std::optional<forecast_policy>& policy, const std::optional<std::uint64_t>& seed, bool on_roads) {
          return scenario_file::load_text(text, source, load_options_of(set, policy, seed, on_roads));
        },
        py::arg("text"), py::arg("source") = "<text>", py::kw_only(), py::arg("set") = py::none(),
        py::arg("policy") = py::none(), py::arg("seed") = py::none(), py::arg("on_roads") = false,
        "As load, from the YAML text itself.");
  m.def("scenario_text", py::overload_cast<const sim::scenario&>(&scenario_file::scenario_text), py::arg("scenario"),
        "The scenario file (YAML) that loads as `scenario`, bit for bit: every field given, SI units, start times "
        "resolved (docs/scenario-format.md). ValueError when the scenario is invalid or no file can state it.");
  m.def("scenario_text", py::overload_cast<const loaded_scenario&>(&scenario_file::scenario_text), py::arg("scenario"),
        "As scenario_text(scenario.scenario), with the roundabout and roads the file declared (drawn, not run).");
  m.def("write_scenario",
        py::overload_cast<const sim::scenario&, const std::filesystem::path&>(&scenario_file::write_file),
        py::arg("scenario"), py::arg("file"),
        "Writes scenario_text(scenario) to `file`, which `maneuvermap run FILE` and mm.sim.load then run and load as "
        "this scenario.");
  m.def("write_scenario",
        py::overload_cast<const loaded_scenario&, const std::filesystem::path&>(&scenario_file::write_file),
        py::arg("scenario"), py::arg("file"), "Writes scenario_text(scenario) of a loaded scenario to `file`.");
}

void bind_simulation(py::module_& m) {
  py::enum_<sim::agent_kind>(m, "agent_kind")
      .value("planning_vehicle", sim::agent_kind::planning_vehicle)
      .value("scripted_vehicle", sim::agent_kind::scripted_vehicle)
      .value("pedestrian", sim::agent_kind::pedestrian)
      .value("static_obstacle", sim::agent_kind::static_obstacle);
  py::enum_<sim::agent_status>(m, "agent_status")
      .value("not_started", sim::agent_status::not_started)
      .value("waiting", sim::agent_status::waiting)
      .value("active", sim::agent_status::active)
      .value("stopped", sim::agent_status::stopped)
      .value("crashed", sim::agent_status::crashed)
      .value("finished", sim::agent_status::finished);
  py::enum_<sim::bypass_side>(m, "bypass_side")
      .value("none", sim::bypass_side::none)
      .value("left", sim::bypass_side::left)
      .value("right", sim::bypass_side::right);

  py::class_<sim::agent_info> info(m, "agent_info", "The fixed description of an agent.");
  pickled_by_members(info, &sim::agent_info::name, &sim::agent_info::kind, &sim::agent_info::shape);
  info.def_readonly("name", &sim::agent_info::name)
      .def_readonly("kind", &sim::agent_info::kind)
      .def_readonly("shape", &sim::agent_info::shape, "about its reference point")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::class_<sim::agent_state> state(m, "agent_state", "The true state of an agent at the current time.");
  pickled_by_members(state, &sim::agent_state::status, &sim::agent_state::pose, &sim::agent_state::speed,
                     &sim::agent_state::acceleration, &sim::agent_state::curvature, &sim::agent_state::arc_length,
                     &sim::agent_state::lateral_offset);
  state.def_readonly("status", &sim::agent_state::status)
      .def_readonly("pose", &sim::agent_state::pose, "[m], heading wrapped to (−π, π]")
      .def_readonly("speed", &sim::agent_state::speed, "[m/s]")
      .def_readonly("acceleration", &sim::agent_state::acceleration, "over the coming step [m/s²]")
      .def_readonly("curvature", &sim::agent_state::curvature, "over the coming step [1/m]")
      .def_readonly("arc_length", &sim::agent_state::arc_length, "on its path [m]")
      .def_readonly("lateral_offset", &sim::agent_state::lateral_offset, "from its path [m], left positive")
      .def("present", &sim::agent_state::present, "observed and collidable")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::class_<sim::plan_record> plan(m, "plan_record", "The last planning step of a planning vehicle.");
  pickled_by_members(plan, &sim::plan_record::time, &sim::plan_record::result, &sim::plan_record::cpu_time_us);
  plan.def_readonly("time", &sim::plan_record::time, "[s]")
      .def_readonly("result", &sim::plan_record::result)
      .def_readonly("cpu_time_us", &sim::plan_record::cpu_time_us, "[µs]; 0 unless measured")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::class_<sim::crash_event> crash(m, "crash_event", "An overlap of two agents, one of them a planning vehicle.");
  pickled_by_members(crash, &sim::crash_event::time, &sim::crash_event::first, &sim::crash_event::second);
  crash.def_readonly("time", &sim::crash_event::time, "[s]")
      .def_readonly("first", &sim::crash_event::first)
      .def_readonly("second", &sim::crash_event::second)
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::class_<sim::run_metrics> metrics(m, "run_metrics", "The run metrics of one planning vehicle (spec §12).");
  pickled_by_members(metrics, &sim::run_metrics::agent, &sim::run_metrics::crash, &sim::run_metrics::crash_time_s,
                     &sim::run_metrics::crash_with, &sim::run_metrics::min_dist_m, &sim::run_metrics::min_dist_time_s,
                     &sim::run_metrics::closest_agent, &sim::run_metrics::ttc_at_min_s, &sim::run_metrics::speed_kmh,
                     &sim::run_metrics::bypass, &sim::run_metrics::lateral_offset_at_min_m,
                     &sim::run_metrics::max_lateral_offset_m, &sim::run_metrics::min_speed_kmh,
                     &sim::run_metrics::max_speed_kmh, &sim::run_metrics::time_in_brake_s,
                     &sim::run_metrics::time_in_accel_s, &sim::run_metrics::planning_steps,
                     &sim::run_metrics::cpu_median_us, &sim::run_metrics::cpu_p99_us);
  metrics.def_readonly("agent", &sim::run_metrics::agent)
      .def_readonly("crash", &sim::run_metrics::crash)
      .def_readonly("crash_time_s", &sim::run_metrics::crash_time_s)
      .def_readonly("crash_with", &sim::run_metrics::crash_with)
      .def_readonly("min_dist_m", &sim::run_metrics::min_dist_m)
      .def_readonly("min_dist_time_s", &sim::run_metrics::min_dist_time_s)
      .def_readonly("closest_agent", &sim::run_metrics::closest_agent)
      .def_readonly("ttc_at_min_s", &sim::run_metrics::ttc_at_min_s)
      .def_readonly("speed_kmh", &sim::run_metrics::speed_kmh)
      .def_readonly("bypass", &sim::run_metrics::bypass)
      .def_readonly("lateral_offset_at_min_m", &sim::run_metrics::lateral_offset_at_min_m)
      .def_readonly("max_lateral_offset_m", &sim::run_metrics::max_lateral_offset_m)
      .def_readonly("min_speed_kmh", &sim::run_metrics::min_speed_kmh)
      .def_readonly("max_speed_kmh", &sim::run_metrics::max_speed_kmh)
      .def_readonly("time_in_brake_s", &sim::run_metrics::time_in_brake_s)
      .def_readonly("time_in_accel_s", &sim::run_metrics::time_in_accel_s)
      .def_readonly("planning_steps", &sim::run_metrics::planning_steps)
      .def_readonly("cpu_median_us", &sim::run_metrics::cpu_median_us)
      .def_readonly("cpu_p99_us", &sim::run_metrics::cpu_p99_us)
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<sim::simulation>(m, "simulation",
                              "A run of a scenario on a fixed time grid, step by step (docs/simulator.md).")
      .def(py::init([](const loaded_scenario& loaded, std::size_t jobs, bool map_columns, bool measure_cpu_time,
                       bool decision_only) {
             return start(loaded.scenario, run_options_of(jobs, map_columns, measure_cpu_time, decision_only));
           }),
           py::arg("scenario"), py::kw_only(), py::arg("jobs") = 1, py::arg("map_columns") = true,
           py::arg("measure_cpu_time") = false, py::arg("decision_only") = false,
           "Places every agent at t = 0 and makes the first decisions. ValueError when the scenario is invalid.")
      .def(py::init([](const sim::scenario& s, std::size_t jobs, bool map_columns, bool measure_cpu_time,
                       bool decision_only) {
             return start(s, run_options_of(jobs, map_columns, measure_cpu_time, decision_only));
           }),
           py::arg("scenario"), py::kw_only(), py::arg("jobs") = 1, py::arg("map_columns") = true,
           py::arg("measure_cpu_time") = false, py::arg("decision_only") = false)
      .def("step", &sim::simulation::step,
           "Advances one time step: motion, crashes, metrics, sensing and decisions. No-op once ended.")
      .def("ended", &sim::simulation::ended)
      .def_property_readonly("time", &sim::simulation::time, "t_k [s]")
      .def_property_readonly("step_index", &sim::simulation::step_index, "k")
      .def_property_readonly("agent_count", &sim::simulation::agent_count)
      .def_property_readonly("planning_vehicle_count", &sim::simulation::planning_vehicle_count,
                             "their ids are 0..count−1")
      .def("info", &sim::simulation::info, py::arg("id"), py::return_value_policy::copy)
      .def("state", &sim::simulation::state, py::arg("id"), py::return_value_policy::copy)
      .def("find", &sim::simulation::find, py::arg("name"), "The id of the agent called `name`, or None.")
      .def("last_plan",
           [](const sim::simulation& s, agent_id id) -> std::optional<sim::plan_record> {
             const sim::plan_record* p = s.last_plan(id);
             if (p == nullptr) return std::nullopt;
             return *p;
           },
           py::arg("id"), "The last planning step of planning vehicle `id`, or None.")
      .def("planned_now", &sim::simulation::planned_now, py::arg("id"))
      .def("planning_input", &sim::simulation::planning_input, py::arg("id"),
           "The input planning vehicle `id` plans on now (None when it is not in the world).")
      .def("override_command", &sim::simulation::override_command, py::arg("id"), py::arg("command"),
           "Drives planning vehicle `id` with `command` from now until its next decision, instead of the one it "
           "decided (your own controller in the loop); it still senses and plans. ValueError when it is not active "
           "or the command is beyond its limits.")
      .def("crashes", [](const sim::simulation& s) {
        return std::vector<sim::crash_event>(s.crashes().begin(), s.crashes().end());
      })
      .def("metrics", &sim::simulation::metrics, py::arg("id"), "spec §12")
      .def("all_metrics", &sim::simulation::all_metrics)
      .def("run", [](sim::simulation& s) { sim::run(s); }, "Steps to the end.");

  py::class_<map_record> map_type(
      m, "map_record", "The Maneuverability Map of one planning vehicle over a run: a row per planning step.");
  pickled_by_members(map_type, &map_record::agent, &map_record::times, &map_record::forecast_times,
                     &map_record::mi_brake, &map_record::mi_accelerate, &map_record::excluded,
                     &map_record::forecast_time, &map_record::selected_family, &map_record::mode,
                     &map_record::time_to_collision, &map_record::command_acceleration,
                     &map_record::command_curvature, &map_record::cpu_time_us, &map_record::robust,
                     &map_record::indices_computed);
  map_type.def_readonly("agent", &map_record::agent)
      .def_property_readonly("times", [](const map_record& r) { return array_of(r.times); }, "[s], shape (steps,)")
      .def_property_readonly("forecast_times", [](const map_record& r) { return array_of(r.forecast_times); },
                             "τ_i [s]")
      .def_property_readonly("mi_brake", [](const map_record& r) { return index_matrix(r, r.mi_brake); },
                             "MI−, shape (steps, forecast times); (steps, 0) without map columns (the run's "
                             "map_columns or the planner's map_column false)")
      .def_property_readonly("mi_accelerate", [](const map_record& r) { return index_matrix(r, r.mi_accelerate); },
                             "MI+, shape (steps, forecast times); (steps, 0) without map columns")
      .def_property_readonly("excluded", [](const map_record& r) {
        return matrix_of<bool>(r.excluded, r.forecast_times.size());
      }, "τ_i > TTC, shape (steps, forecast times)")
      .def_property_readonly("forecast_time", [](const map_record& r) { return array_of(r.forecast_time); },
                             "τ̄ [s]; 0 where indices_computed is False")
      .def_property_readonly("indices_computed", [](const map_record& r) { return flags_of(r.indices_computed); },
                             "False at the steps a run with decision_only decided without any index (u_nom proven "
                             "safe under every forecast time): τ̄, the family and the selected indices not computed")
      .def_property_readonly("selected_family", [](const map_record& r) { return array_of(r.selected_family); },
                             "int(maneuvermap.family.…)")
      .def_property_readonly("mode", [](const map_record& r) { return array_of(r.mode); },
                             "int(maneuvermap.planning_mode.…)")
      .def_property_readonly("robust", [](const map_record& r) { return flags_of(r.robust); },
                             "the robust policy's sets decided (plan_result.robust), per step")
      .def_property_readonly("time_to_collision", [](const map_record& r) { return array_of(r.time_to_collision); },
                             "[s], inf for none")
      .def_property_readonly("command_acceleration",
                             [](const map_record& r) { return array_of(r.command_acceleration); }, "[m/s²]")
      .def_property_readonly("command_curvature", [](const map_record& r) { return array_of(r.command_curvature); },
                             "[1/m]")
      .def_property_readonly("cpu_time_us", [](const map_record& r) { return array_of(r.cpu_time_us); },
                             "[µs]; 0 unless measure_cpu_time")
      .def("__repr__", [](const map_record& r) {
        return "map_record(agent=" + py::repr(py::str(r.agent)).cast<std::string>() + ", " +
               std::to_string(r.times.size()) + " planning steps)";
      });

  py::class_<run_record> run(m, "run_record",
                             "A whole run: every agent's state at every step (arrays of shape (steps, agents)), "
                             "every planning vehicle's map, the metrics and the crashes.");
  pickled_by_members(run, &run_record::scenario, &run_record::source, &run_record::agents, &run_record::times,
                     &run_record::agent_count, &run_record::x, &run_record::y, &run_record::heading,
                     &run_record::speed, &run_record::acceleration, &run_record::curvature, &run_record::arc_length,
                     &run_record::lateral_offset, &run_record::status, &run_record::maps, &run_record::metrics,
                     &run_record::crashes);
  run.def_readonly("scenario", &run_record::scenario, "its name")
      .def_readonly("source", &run_record::source)
      .def_readonly("agents", &run_record::agents, "in id order: planning vehicles first")
      .def_property_readonly("times", [](const run_record& r) { return array_of(r.times); }, "t_k [s]")
      .def_property_readonly("x", [](const run_record& r) { return matrix_of(r.x, r.agent_count); }, "[m]")
      .def_property_readonly("y", [](const run_record& r) { return matrix_of(r.y, r.agent_count); }, "[m]")
      .def_property_readonly("heading", [](const run_record& r) { return matrix_of(r.heading, r.agent_count); },
                             "[rad]")
      .def_property_readonly("speed", [](const run_record& r) { return matrix_of(r.speed, r.agent_count); }, "[m/s]")
      .def_property_readonly("acceleration",
                             [](const run_record& r) { return matrix_of(r.acceleration, r.agent_count); },
                             "applied over the coming step [m/s²]")
      .def_property_readonly("curvature", [](const run_record& r) { return matrix_of(r.curvature, r.agent_count); },
                             "applied over the coming step [1/m]")
      .def_property_readonly("arc_length", [](const run_record& r) { return matrix_of(r.arc_length, r.agent_count); },
                             "[m]")
      .def_property_readonly("lateral_offset",
                             [](const run_record& r) { return matrix_of(r.lateral_offset, r.agent_count); }, "[m]")
      .def_property_readonly("status",
                             [](const run_record& r) { return matrix_of<std::uint8_t>(r.status, r.agent_count); },
                             "int(maneuvermap.sim.agent_status.…)")
      .def_property_readonly("present", [](const run_record& r) {
        std::vector<std::uint8_t> present;
        for (std::uint8_t s : r.status) present.push_back(sim::is_present(static_cast<sim::agent_status>(s)) ? 1 : 0);
        return matrix_of<bool>(present, r.agent_count);
      }, "observed and collidable: the rows of maneuvermap run's trajectories.csv")
      .def_readonly("maps", &run_record::maps, "one per planning vehicle, in id order")
      .def("map", [](const run_record& r, const std::string& agent) {
        for (const map_record& map : r.maps) {
          if (map.agent == agent) return map;
        }
        throw py::key_error("no planning vehicle called '" + agent + "'");
      }, py::arg("agent"), "The map of the planning vehicle called `agent`.")
      .def_readonly("metrics", &run_record::metrics, "spec §12, one per planning vehicle")
      .def_readonly("crashes", &run_record::crashes)
      .def("__repr__", [](const run_record& r) {
        return "run_record(scenario=" + py::repr(py::str(r.scenario)).cast<std::string>() + ", " +
               std::to_string(r.times.size()) + " instants, " + std::to_string(r.agent_count) + " agents)";
      });

  m.def("run",
        [](const py::object& what, const std::optional<std::map<std::string, double>>& set,
           const std::optional<forecast_policy>& policy, const std::optional<std::uint64_t>& seed, bool on_roads,
           std::size_t jobs, bool map_columns, bool measure_cpu_time, bool decision_only) {
          const loaded_scenario loaded = loaded_from("run", what, set, policy, seed, on_roads);
          const sim::run_options options = run_options_of(jobs, map_columns, measure_cpu_time, decision_only);
          const py::gil_scoped_release release;
          return run_whole(loaded, options);
        },
        py::arg("scenario"), py::kw_only(), py::arg("set") = py::none(), py::arg("policy") = py::none(),
        py::arg("seed") = py::none(), py::arg("on_roads") = false, py::arg("jobs") = 1, py::arg("map_columns") = true,
        py::arg("measure_cpu_time") = false, py::arg("decision_only") = false,
        "Runs a scenario (a built-in name, a file, a loaded_scenario or a scenario) to its end and returns its "
        "run_record: what `maneuvermap run` writes, as arrays. decision_only: no map column (whatever "
        "map_columns says), and steps whose nominal maneuver is proven safe under every forecast time compute no "
        "index (the same run; their rows of the maps have indices_computed False). Releases the GIL.");

  m.def("write_run",
        [](const py::object& what, const std::filesystem::path& out_dir,
           const std::optional<std::map<std::string, double>>& set, const std::optional<forecast_policy>& policy,
           const std::optional<std::uint64_t>& seed, bool on_roads, std::size_t jobs, bool measure_cpu_time,
           const std::optional<std::filesystem::path>& commonroad, double commonroad_step) {
          const loaded_scenario loaded = loaded_from("write_run", what, set, policy, seed, on_roads);
          cli::run_settings settings;
          settings.out_dir = out_dir;
          if (commonroad) settings.commonroad_file = *commonroad;
          settings.commonroad_step = commonroad_step;
          settings.jobs = run_options_of(jobs, true, measure_cpu_time).jobs;
          settings.measure_cpu_time = measure_cpu_time;
          const py::gil_scoped_release release;
          return cli::run_scenario(loaded, settings).files;
        },
        py::arg("scenario"), py::arg("out_dir"), py::kw_only(), py::arg("set") = py::none(),
        py::arg("policy") = py::none(), py::arg("seed") = py::none(), py::arg("on_roads") = false, py::arg("jobs") = 1,
        py::arg("measure_cpu_time") = false, py::arg("commonroad") = py::none(), py::arg("commonroad_step") = 0.1,
        "Runs a scenario as `run` does and writes the files of `maneuvermap run --out out_dir` (trajectories.csv, "
        "map.csv, decisions.csv, summary.json, scene.json; docs/outputs.md), which `maneuvermap plot` draws; "
        "with `commonroad` also the run as a CommonRoad recording at `commonroad_step` [s] (`--commonroad`); "
        "returns their paths. Releases the GIL.");
}

}  // namespace

void bind_sim(py::module_& m) {
  bind_scenario_values(m);
  bind_scenarios(m);
  bind_simulation(m);
}

}  // namespace mm::python
