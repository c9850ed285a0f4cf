// Bindings of the CommonRoad reader and measurement (docs/python.md, docs/commonroad.md): read a
// recording, then measure the room to maneuver of its road users step by step.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "mm/commonroad/writer.hpp"
#include "fields.hpp"
#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/reader.hpp"
#include "mm/commonroad/replay.hpp"

namespace mm::python {

namespace {

namespace cr = mm::commonroad;

template <class F>
py::array_t<double> column_of(const std::vector<cr::state>& states, F value) {
  std::vector<double> out;
  out.reserve(states.size());
  for (const cr::state& s : states) out.push_back(value(s));
  return array_of(out);
}

/// An (steps × forecast times) array of one index over a measurement.
template <class F>
py::array_t<double> map_of(const cr::measurement& m, F column) {
  const std::size_t columns = m.steps.empty() ? 0 : m.steps.front().result.forecast_times.size();
  py::array_t<double> out({static_cast<py::ssize_t>(m.steps.size()), static_cast<py::ssize_t>(columns)});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < m.steps.size(); ++k) {
    const std::vector<double>& values = column(m.steps[k].result);
    for (std::size_t i = 0; i < columns; ++i) {
      view(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(i)) = i < values.size() ? values[i] : 0.0;
    }
  }
  return out;
}

cr::measure_options options_of(std::uint32_t agent, const std::optional<planner_config>& config,
                               const std::optional<forecast_policy>& policy, const std::optional<ego_limits>& limits,
                               const cr::scenario* on_lanelets = nullptr) {
  cr::measure_options options;
  options.agent = agent;
  if (on_lanelets != nullptr) {
    try {
      options.drivable_area = std::make_shared<const drivable_area>(cr::lanelet_polygons(*on_lanelets));
    } catch (const std::invalid_argument& e) {
      throw cr::measure_error(std::string("on_lanelets: ") + e.what());
    }
  }
  if (config) options.config = *config;
  if (policy) options.config.policy = *policy;
  if (limits) options.limits = *limits;
  return options;
}

}  // namespace

void bind_commonroad(py::module_& m) {
  py::register_exception<cr::read_error>(m, "read_error", PyExc_ValueError);
  py::register_exception<cr::measure_error>(m, "measure_error", PyExc_ValueError);

  py::class_<cr::state> state_type(m, "state", "One recorded state of a road user.");
  pickled_by_members(state_type, &cr::state::step, &cr::state::position, &cr::state::orientation, &cr::state::velocity,
                     &cr::state::yaw_rate, &cr::state::acceleration);
  state_type
      .def_readonly("step", &cr::state::step, "time step k; the time is k·time_step [s]")
      .def_readonly("position", &cr::state::position, "centre of the shape [m]")
      .def_readonly("orientation", &cr::state::orientation, "[rad], as in the file")
      .def_readonly("velocity", &cr::state::velocity, "[m/s]")
      .def_readonly("yaw_rate", &cr::state::yaw_rate, "[rad/s] or None")
      .def_readonly("acceleration", &cr::state::acceleration, "[m/s²] or None")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::enum_<cr::obstacle_role>(m, "obstacle_role")
      .value("dynamic_obstacle", cr::obstacle_role::dynamic_obstacle)
      .value("static_obstacle", cr::obstacle_role::static_obstacle);
  py::class_<cr::obstacle> obstacle_type(m, "obstacle", "A road user or static obstacle of the file.");
  pickled_by_members(obstacle_type, &cr::obstacle::id, &cr::obstacle::role, &cr::obstacle::type, &cr::obstacle::shape,
                     &cr::obstacle::states);
  obstacle_type
      .def_readonly("id", &cr::obstacle::id)
      .def_readonly("role", &cr::obstacle::role)
      .def_readonly("type", &cr::obstacle::type, "car, truck, bus, bicycle, pedestrian, …")
      .def_readonly("shape", &cr::obstacle::shape, "about the state's position and orientation")
      .def_readonly("states", &cr::obstacle::states, "at consecutive steps")
      .def_property_readonly("steps", [](const cr::obstacle& o) {
        std::vector<std::int64_t> steps;
        for (const cr::state& s : o.states) steps.push_back(s.step);
        return array_of(steps);
      }, "the states' time steps k")
      .def_property_readonly("positions", [](const cr::obstacle& o) {
        std::vector<vec2> points;
        for (const cr::state& s : o.states) points.push_back(s.position);
        return points_of(points);
      }, "[m], shape (states, 2)")
      .def_property_readonly("orientations", [](const cr::obstacle& o) {
        return column_of(o.states, [](const cr::state& s) { return s.orientation; });
      }, "[rad]")
      .def_property_readonly("velocities", [](const cr::obstacle& o) {
        return column_of(o.states, [](const cr::state& s) { return s.velocity; });
      }, "[m/s]")
      .def("__repr__", [](const cr::obstacle& o) {
        return "obstacle(id=" + std::to_string(o.id) + ", type=" + py::repr(py::str(o.type)).cast<std::string>() +
               ", " + std::to_string(o.states.size()) + " states)";
      });
  py::class_<cr::lanelet> lanelet_type(m, "lanelet", "A lane: its two bounds, in the driving direction, and its links.");
  pickled_by_members(lanelet_type, &cr::lanelet::id, &cr::lanelet::left_bound, &cr::lanelet::right_bound,
                     &cr::lanelet::predecessors, &cr::lanelet::successors);
  lanelet_type
      .def_readonly("id", &cr::lanelet::id)
      .def_property_readonly("left_bound", [](const cr::lanelet& l) { return points_of(l.left_bound); },
                             "[m], shape (points, 2)")
      .def_property_readonly("right_bound", [](const cr::lanelet& l) { return points_of(l.right_bound); },
                             "[m], shape (points, 2)")
      .def_readonly("predecessors", &cr::lanelet::predecessors, "ids of the lanelets it continues")
      .def_readonly("successors", &cr::lanelet::successors, "ids of the lanelets that continue it")
      .def("__repr__", [](const cr::lanelet& l) { return "lanelet(id=" + std::to_string(l.id) + ")"; });
  py::class_<cr::planning_problem> problem_type(m, "planning_problem", "The start of an ego task of the file.");
  pickled_by_members(problem_type, &cr::planning_problem::id, &cr::planning_problem::initial);
  problem_type
      .def_readonly("id", &cr::planning_problem::id)
      .def_readonly("initial", &cr::planning_problem::initial)
      .def("__repr__", [](py::handle self) { return fields_repr(self); });
  py::class_<cr::scenario> scenario_type(m, "scenario",
                                         "What a CommonRoad file holds, as far as measuring needs it; pickles by its "
                                         "values (for a process pool), and == compares them all.");
  pickled_by_members(scenario_type, &cr::scenario::benchmark_id, &cr::scenario::version, &cr::scenario::date,
                     &cr::scenario::time_step, &cr::scenario::lanelets, &cr::scenario::obstacles,
                     &cr::scenario::planning_problems);
  scenario_type
      .def("__eq__", [](const cr::scenario& a, py::handle b) {
        return py::isinstance<cr::scenario>(b) && a == b.cast<const cr::scenario&>();
      })
      .def_readonly("benchmark_id", &cr::scenario::benchmark_id)
      .def_readonly("version", &cr::scenario::version, "2018b or 2020a")
      .def_readonly("date", &cr::scenario::date, "the file's date, YYYY-MM-DD, or empty")
      .def_readonly("time_step", &cr::scenario::time_step, "[s]")
      .def_readonly("lanelets", &cr::scenario::lanelets)
      .def_readonly("obstacles", &cr::scenario::obstacles, "in file order")
      .def_readonly("planning_problems", &cr::scenario::planning_problems)
      .def("obstacle", [](const cr::scenario& s, std::uint32_t id) {
        for (const cr::obstacle& o : s.obstacles) {
          if (o.id == id) return o;
        }
        throw py::key_error("no obstacle with id " + std::to_string(id));
      }, py::arg("id"))
      .def("__repr__", [](const cr::scenario& s) {
        return "scenario(benchmark_id=" + py::repr(py::str(s.benchmark_id)).cast<std::string>() + ", " +
               std::to_string(s.obstacles.size()) + " obstacles)";
      });
  scenario_type.attr("__hash__") = py::none();

  m.def("read_scenario", [](const std::filesystem::path& file) { return cr::read_scenario(file); }, py::arg("file"),
        py::call_guard<py::gil_scoped_release>(),
        "Reads a CommonRoad file (2018b or 2020a). read_error (a ValueError) names the file, line, element, "
        "field and value of any problem.");
  m.def("read_scenario_text", &cr::read_scenario_text, py::arg("text"), py::arg("source") = "<text>",
        py::call_guard<py::gil_scoped_release>(), "As read_scenario, from the XML text itself.");
  m.def("scenario_xml", &cr::scenario_xml, py::arg("scenario"),
        "The CommonRoad XML (2020a, with what its schema requires) that read_scenario_text reads as `scenario` "
        "again, bit for bit, but for its version (2020a), its date when it has none (1970-01-01), its static "
        "obstacles first and a planning problem's missing yaw rate (0); ValueError when it would not.");
  m.def("write_scenario", &cr::write_scenario, py::arg("scenario"), py::arg("file"),
        "Writes scenario_xml(scenario) to `file`.");

  py::class_<cr::measured_step> step_type(m, "measured_step",
                                          "The planner's view of the measured road user at one step.");
  pickled_by_members(step_type, &cr::measured_step::step, &cr::measured_step::time, &cr::measured_step::ego,
                     &cr::measured_step::recorded, &cr::measured_step::obstacle_ids, &cr::measured_step::result);
  step_type.def_readonly("step", &cr::measured_step::step)
      .def_readonly("time", &cr::measured_step::time, "[s]")
      .def_readonly("ego", &cr::measured_step::ego, "as recorded")
      .def_readonly("recorded", &cr::measured_step::recorded, "what it did next: the planner's u_nom")
      .def_readonly("obstacle_ids", &cr::measured_step::obstacle_ids, "in result.obstacles order")
      .def_readonly("result", &cr::measured_step::result)
      .def("__repr__", [](const cr::measured_step& s) {
        return "measured_step(step=" + std::to_string(s.step) +
               ", room=" + py::repr(py::float_(cr::room(s.result))).cast<std::string>() + ")";
      });
  py::class_<cr::measurement> measurement_type(m, "measurement", "Every recorded step of one road user, planned on.");
  pickled_by_members(measurement_type, &cr::measurement::agent, &cr::measurement::steps);
  measurement_type.def_readonly("agent", &cr::measurement::agent)
      .def_readonly("steps", &cr::measurement::steps)
      .def_property_readonly("times", [](const cr::measurement& r) {
        std::vector<double> t;
        for (const cr::measured_step& s : r.steps) t.push_back(s.time);
        return array_of(t);
      }, "[s]")
      .def_property_readonly("rooms", [](const cr::measurement& r) {
        std::vector<double> rooms;
        for (const cr::measured_step& s : r.steps) rooms.push_back(cr::room(s.result));
        return array_of(rooms);
      }, "max(MI−, MI+) under the selected forecast times at every step, in [0, 1]")
      .def_property_readonly("forecast_times", [](const cr::measurement& r) {
        return r.steps.empty() ? array_of(std::vector<double>{}) : array_of(r.steps.front().result.forecast_times);
      }, "τ_i [s]")
      .def_property_readonly("mi_brake", [](const cr::measurement& r) {
        return map_of(r, [](const plan_result& p) -> const std::vector<double>& { return p.mi_brake; });
      }, "MI−, shape (steps, forecast times)")
      .def_property_readonly("mi_accelerate", [](const cr::measurement& r) {
        return map_of(r, [](const plan_result& p) -> const std::vector<double>& { return p.mi_accelerate; });
      }, "MI+, shape (steps, forecast times)")
      .def("__repr__", [](const cr::measurement& r) {
        return "measurement(agent=" + std::to_string(r.agent) + ", " + std::to_string(r.steps.size()) + " steps)";
      });

  m.def("measure",
        [](const cr::scenario& s, std::uint32_t agent, const std::optional<planner_config>& config,
           const std::optional<forecast_policy>& policy, const std::optional<ego_limits>& limits, bool on_lanelets) {
          return cr::measure(s, options_of(agent, config, policy, limits, on_lanelets ? &s : nullptr));
        },
        py::arg("scenario"), py::arg("agent"), py::kw_only(), py::arg("config") = py::none(),
        py::arg("policy") = py::none(), py::arg("limits") = py::none(), py::arg("on_lanelets") = false,
        py::call_guard<py::gil_scoped_release>(),
        "Plans road user `agent` at every recorded step (open loop: the recording is not changed) and returns "
        "its Maneuverability Map and room, as `maneuvermap measure` (docs/commonroad.md); on_lanelets: only the "
        "room on the union of the file's lanelets (spec §5's road constraint, `--on-lanelets`). measure_error (a "
        "ValueError) when it cannot be measured. Releases the GIL.");
  m.def("planning_input",
        [](const cr::scenario& s, std::uint32_t agent, std::int64_t step, const std::optional<planner_config>& config,
           const std::optional<forecast_policy>& policy, const std::optional<ego_limits>& limits, bool on_lanelets) {
          std::vector<std::uint32_t> ids;
          plan_input input =
              cr::planning_input(s, options_of(agent, config, policy, limits, on_lanelets ? &s : nullptr), step, &ids);
          return py::make_tuple(input, ids);
        },
        py::arg("scenario"), py::arg("agent"), py::arg("step"), py::kw_only(), py::arg("config") = py::none(),
        py::arg("policy") = py::none(), py::arg("limits") = py::none(), py::arg("on_lanelets") = false,
        "(plan_input, obstacle ids): the planner's input for road user `agent` at recorded step `step`.");
  m.def("replay_scenario",
        [](const cr::scenario& s, std::uint32_t agent, const std::optional<planner_config>& config,
           const std::optional<forecast_policy>& policy, const std::optional<ego_limits>& limits,
           const std::optional<double>& desired_speed, bool avoidance, bool on_lanelets, bool reactive) {
          cr::replay_options options;
          const cr::measure_options measured = options_of(agent, config, policy, limits);
          options.agent = agent;
          options.config = measured.config;
          options.limits = measured.limits;
          options.desired_speed = desired_speed;
          options.avoidance = avoidance;
          options.on_lanelets = on_lanelets;
          if (reactive) options.reactive = cr::reactive_traffic();
          return cr::replay_scenario(s, options);
        },
        py::arg("scenario"), py::arg("agent"), py::kw_only(), py::arg("config") = py::none(),
        py::arg("policy") = py::none(), py::arg("limits") = py::none(), py::arg("desired_speed") = py::none(),
        py::arg("avoidance") = true, py::arg("on_lanelets") = false, py::arg("reactive") = false,
        "The recording as a simulation scenario with road user `agent` driven by the planner along its recorded "
        "path and the others replayed (docs/commonroad.md); with reactive=True the other vehicles keep their "
        "distance to the road user ahead on their paths, lagging behind their recordings where they must. Run it "
        "with maneuvermap.sim.run. measure_error when it cannot be replayed.");
  m.def("measurable_road_users", &cr::measurable_road_users, py::arg("scenario"),
        "The dynamic obstacles that are not pedestrians, in file order.");
  m.def("recorded_ego", &cr::recorded_ego, py::arg("scenario"), py::arg("problem"),
        "The obstacle that replays the planning problem's ego, or None (docs/commonroad.md).");
  m.def("room", &cr::room, py::arg("result"), "max(MI−, MI+) under the selected forecast times, in [0, 1].");
}

}  // namespace mm::python
