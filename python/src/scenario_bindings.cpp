// Bindings of the simulator's scenario (docs/python.md, "A scenario built in Python"): the scenario,
// its agents, their paths, speed profiles and stops, to build a scenario in Python or change a loaded
// one before its run.
#include "scenario_bindings.hpp"

#include <pybind11/stl.h>
#include <pybind11/stl_bind.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fields.hpp"
#include "mm/drivable_area.hpp"
#include "mm/scenario_file/loader.hpp"
#include "mm/scenario_file/writer.hpp"
#include "mm/sim/follower.hpp"
#include "mm/sim/path.hpp"
#include "mm/sim/scripted.hpp"

namespace mm::python {

namespace {

/// Points of `p` about `spacing` [m] apart, both ends included, as a (points, 2) array.
py::array_t<double> path_points(const sim::path& p, double spacing) {
  const double length = p.length();
  if (!(spacing > 0.0) || !std::isfinite(spacing) || length / spacing > 1e6) {
    throw py::value_error("spacing = " + py::repr(py::float_(spacing)).cast<std::string>() +
                          ": expected a positive number of metres giving at most a million points");
  }
  if (p.empty()) throw py::value_error("the path is empty: it has no points");
  std::vector<vec2> points;
  const auto pieces = std::max<std::size_t>(static_cast<std::size_t>(std::ceil(length / spacing)), 1);
  for (std::size_t k = 0; k <= pieces; ++k) {
    points.push_back(p.at(length * static_cast<double>(k) / static_cast<double>(pieces)).position);
  }
  return points_of(points);
}

/// The list-like view of a scenario's agents of one kind (`scenario.pedestrians.append(p)`), which
/// a Python list may be assigned to, equal to another list of equal agents. The agents' C++ `==`
/// gives it `count`, `remove` and `in`; its `__eq__` is `equal_by_elements`', which takes any
/// object (pybind11's takes only another list of agents).
template <class Agent>
void agent_list(py::module_& m, const char* name) {
  auto list = py::bind_vector<std::vector<Agent>>(m, name);
  py::delattr(list, "__eq__");
  py::delattr(list, "__ne__");
  equal_by_elements(list);
  py::implicitly_convertible<py::list, std::vector<Agent>>();
}

void bind_path(py::module_& m) {
  py::enum_<sim::before_start_behaviour>(m, "before_start_behaviour", "Where an agent is before its start time.")
      .value("absent", sim::before_start_behaviour::absent, "not in the world: neither observed nor collidable")
      .value("wait", sim::before_start_behaviour::wait, "standing at its start pose: observed and collidable");

  py::class_<sim::path_point> point(m, "path_point", "The geometry of a path at one arc length.");
  point.def_readonly("position", &sim::path_point::position, "[m]")
      .def_readonly("heading", &sim::path_point::heading, "tangent direction [rad], wrapped to (−π, π]")
      .def_readonly("curvature", &sim::path_point::curvature, "κ [1/m], left positive")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<sim::path> p(m, "path",
                          "A path of straight lines and circular arcs, by arc length (docs/scenario-format.md's "
                          "`path:`): mm.sim.path(mm.pose(x, y, heading)).straight(20.0).turn(15.0, math.pi / 2).");
  p.def(py::init<>(), "The empty path (not drivable).")
      .def(py::init<const pose&>(), py::arg("start"), "An empty path whose first segment starts at `start`.")
      .def_static("polyline", [](const std::vector<vec2>& points) { return sim::path::polyline(points); },
                  py::arg("points"), "Straight segments through `points` (at least 2, consecutive ones distinct) [m].")
      .def_static("circular_arc", &sim::path::circular_arc, py::arg("center"), py::arg("radius"),
                  py::arg("start_angle"), py::arg("sweep"),
                  "The arc of the circle of `radius` [m] about `center` from polar angle `start_angle` over "
                  "`sweep` [rad], positive counter-clockwise.")
      .def("straight", &sim::path::straight, py::arg("length"), py::return_value_policy::reference_internal,
           "Appends `length` [m] > 0 straight ahead; returns the path.")
      .def("turn", &sim::path::turn, py::arg("radius"), py::arg("angle"), py::return_value_policy::reference_internal,
           "Appends an arc of `radius` [m] > 0 turning by `angle` [rad] (positive left); returns the path.")
      .def("line_to", &sim::path::line_to, py::arg("point"), py::return_value_policy::reference_internal,
           "Appends a straight segment to `point` [m] (a corner unless it lies straight ahead); returns the path.")
      .def("curve", &sim::path::curve, py::arg("length"), py::arg("curvature"), py::return_value_policy::reference_internal,
           "Appends `length` [m] > 0 of constant `curvature` [1/m] (positive left, 0 straight); returns the path.")
      .def_property_readonly("length", &sim::path::length, "L [m]")
      .def_property_readonly("end_pose", &sim::path::end_pose, "where the next segment starts")
      .def("empty", &sim::path::empty)
      .def(
          "at",
          [](const sim::path& path, double arc_length) {
            if (path.empty()) throw py::value_error("the path is empty: it has no points");
            if (!std::isfinite(arc_length)) {
              throw py::value_error("arc_length = " + py::repr(py::float_(arc_length)).cast<std::string>() +
                                    ": expected a finite number [m]");
            }
            return path.at(arc_length);
          },
          py::arg("arc_length"), "Position, heading and curvature at arc length s [m] (straight beyond the ends).")
      .def("points", &path_points, py::arg("spacing") = 0.5, "The path at about `spacing` [m], shape (points, 2) [m]")
      .def("__eq__", [](const sim::path& a, py::handle b) {
        return py::isinstance<sim::path>(b) && a == b.cast<const sim::path&>();
      })
      .def("__repr__", [](const sim::path& path) {
        return "path(" + std::to_string(path.segments().size()) + " segments, length=" +
               py::repr(py::float_(path.length())).cast<std::string>() + ")";
      });
  p.attr("__hash__") = py::none();
  copied_by_value(p);
  // Pickled as the steps that rebuild it bit for bit (sim::steps_of), as a scenario file writes it.
  p.def(py::pickle(
      [](const sim::path& path) {
        const sim::path_steps built = sim::steps_of(path);
        py::list steps;
        for (const sim::path_step& step : built.steps) {
          steps.append(py::make_tuple(static_cast<int>(step.operation), step.length, step.curvature, step.point));
        }
        return py::make_tuple(built.start, steps);
      },
      [](const py::tuple& state) {
        if (state.size() != 2) throw std::runtime_error("cannot unpickle a path: expected (start, steps)");
        sim::path_steps built{state[0].cast<pose>(), {}};
        for (const py::handle item : state[1].cast<py::list>()) {
          const auto step = item.cast<py::tuple>();
          const int operation = step.size() == 4 ? step[0].cast<int>() : -1;
          if (operation < 0 || operation > 2) {
            throw std::runtime_error("cannot unpickle a path: expected steps (operation 0 to 2, length, curvature, point)");
          }
          built.steps.push_back({static_cast<sim::path_step::kind>(operation), step[1].cast<double>(),
                                 step[2].cast<double>(), step[3].cast<vec2>()});
        }
        return sim::path_of(built);
      }));
}

void bind_motions(py::module_& m) {
  py::class_<sim::speed_knot> knot(m, "speed_knot", "One knot of a speed profile.");
  with_fields(knot)
      .def(py::init([](double time, double speed) { return sim::speed_knot{time, speed}; }), py::arg("time"),
           py::arg("speed"))
      .def_readwrite("time", &sim::speed_knot::time, "on the agent's own clock, stops not counted [s], ≥ 0")
      .def_readwrite("speed", &sim::speed_knot::speed, "[m/s], ≥ 0");

  py::class_<sim::speed_profile> profile(
      m, "speed_profile", "Speed as a piecewise-linear function of the agent's own clock (knot times increasing).");
  with_fields(profile)
      .def_readwrite("knots", &sim::speed_profile::knots)
      .def_static("constant", &sim::speed_profile::constant, py::arg("speed"), "A constant speed v [m/s].");

  py::class_<sim::stop_rule> stop(m, "stop_rule", "A stop on the path, e.g. a pedestrian waiting at the kerb.");
  with_fields(stop)
      .def_readwrite("arc_length", &sim::stop_rule::arc_length, "s_stop [m] on the path, ≥ the start arc length")
      .def_readwrite("duration", &sim::stop_rule::duration, "how long it stands [s] > 0; None: for ever");

  py::class_<sim::scripted_motion> motion(
      m, "scripted_motion", "The motion of a scripted agent: along its path exactly, at its speed profile.");
  copied_by_value(with_fields(motion))
      .def_readwrite("path", &sim::scripted_motion::path)
      .def_readwrite("start_time", &sim::scripted_motion::start_time, "[s], ≥ 0")
      .def_readwrite("start_arc_length", &sim::scripted_motion::start_arc_length, "s0 [m], 0 ≤ s0 < path length")
      .def_readwrite("before_start", &sim::scripted_motion::before_start)
      .def_readwrite("speed", &sim::scripted_motion::speed, "on its own clock")
      .def_readwrite("stop", &sim::scripted_motion::stop, "None: no stop");

  py::class_<sim::car_following_config> following(
      m, "car_following_config", "Keeping a distance to the road user ahead on the path (docs/simulator.md §5).");
  with_fields(following)
      .def_readwrite("time_gap", &sim::car_following_config::time_gap, "T [s] ≥ 0")
      .def_readwrite("jam_distance", &sim::car_following_config::jam_distance, "s0 [m] ≥ 0")
      .def_readwrite("corridor_half_width", &sim::car_following_config::corridor_half_width, "[m] > 0")
      .def_readwrite("max_heading_difference", &sim::car_following_config::max_heading_difference, "[rad] in [0, π]");

  py::class_<sim::scripted_car_following> scripted_following(
      m, "scripted_car_following", "Car following for a scripted vehicle: it lags behind its script where it must.");
  with_fields(scripted_following)
      .def_readwrite("following", &sim::scripted_car_following::following)
      .def_readwrite("max_acceleration", &sim::scripted_car_following::max_acceleration, "a [m/s²] > 0")
      .def_readwrite("comfortable_deceleration", &sim::scripted_car_following::comfortable_deceleration,
                     "b [m/s²] > 0")
      .def_readwrite("max_deceleration", &sim::scripted_car_following::max_deceleration, "d_max [m/s²] > 0")
      .def_readwrite("speed_gain", &sim::scripted_car_following::speed_gain, "k_v [1/s] > 0")
      .def_readwrite("follows_scripted", &sim::scripted_car_following::follows_scripted,
                     "False: follow only road users that do not keep to a script");

  py::class_<sim::follower_config> follower(m, "follower_config",
                                            "The path follower that gives u_nom (spec §8; docs/simulator.md §3).");
  with_fields(follower)
      .def_readwrite("lookahead_time", &sim::follower_config::lookahead_time, "k_L [s] > 0")
      .def_readwrite("min_lookahead", &sim::follower_config::min_lookahead, "L_min [m] > 0")
      .def_readwrite("speed_gain", &sim::follower_config::speed_gain, "k_v [1/s] > 0")
      .def_readwrite("comfortable_deceleration", &sim::follower_config::comfortable_deceleration, "b [m/s²] > 0")
      .def_readwrite("curve_lateral_acceleration", &sim::follower_config::curve_lateral_acceleration,
                     "a_lat [m/s²]; None: the vehicle's max_lateral_acceleration")
      .def_readwrite("car_following", &sim::follower_config::car_following, "None: off, as in spec §8");

  py::class_<sim::sensing_noise> noise(m, "sensing_noise",
                                       "Gaussian noise on every observation of a planning vehicle (spec §4).");
  with_fields(noise)
      .def_readwrite("position_sd", &sim::sensing_noise::position_sd, "σ of x and y [m], ≥ 0")
      .def_readwrite("heading_sd", &sim::sensing_noise::heading_sd, "σ [rad], ≥ 0")
      .def_readwrite("speed_sd", &sim::sensing_noise::speed_sd, "σ [m/s], ≥ 0");
}

void bind_agents(py::module_& m) {
  py::class_<sim::planning_vehicle> planning(
      m, "planning_vehicle", "A vehicle that follows its path and avoids the others with the planner.");
  copied_by_value(with_fields(planning))
      .def_readwrite("name", &sim::planning_vehicle::name)
      .def_readwrite("path", &sim::planning_vehicle::path, "its reference path")
      .def_readwrite("start_arc_length", &sim::planning_vehicle::start_arc_length, "s0 [m]")
      .def_readwrite("start_lateral_offset", &sim::planning_vehicle::start_lateral_offset, "[m], left positive")
      .def_readwrite("start_time", &sim::planning_vehicle::start_time, "[s]")
      .def_readwrite("before_start", &sim::planning_vehicle::before_start)
      .def_readwrite("initial_speed", &sim::planning_vehicle::initial_speed, "[m/s]")
      .def_readwrite("desired_speed", &sim::planning_vehicle::desired_speed, "[m/s]")
      .def_readwrite("desired_speed_profile", &sim::planning_vehicle::desired_speed_profile,
                     "None: desired_speed throughout")
      .def_readwrite("shape", &sim::planning_vehicle::shape, "[m]")
      .def_readwrite("limits", &sim::planning_vehicle::limits, "spec §3")
      .def_readwrite("planner", &sim::planning_vehicle::planner, "its planner_config")
      .def_readwrite("follower", &sim::planning_vehicle::follower, "how it drives its path (u_nom)")
      .def_readwrite("avoidance", &sim::planning_vehicle::avoidance, "False: u_nom without planning")
      .def_readwrite("planning_period", &sim::planning_vehicle::planning_period, "plan every k-th step")
      .def(
          "path_points", [](const sim::planning_vehicle& v, double spacing) { return path_points(v.path, spacing); },
          py::arg("spacing") = 0.5, "Its reference path at about `spacing` [m], shape (points, 2) [m]");
  agent_list<sim::planning_vehicle>(m, "planning_vehicle_list");

  py::class_<sim::scripted_vehicle> scripted(
      m, "scripted_vehicle", "A vehicle that replays its motion, ignoring the others unless it follows (the paper's B).");
  copied_by_value(with_fields(scripted))
      .def_readwrite("name", &sim::scripted_vehicle::name)
      .def_readwrite("motion", &sim::scripted_vehicle::motion)
      .def_readwrite("shape", &sim::scripted_vehicle::shape, "[m]")
      .def_readwrite("car_following", &sim::scripted_vehicle::car_following, "None: exactly its motion");
  agent_list<sim::scripted_vehicle>(m, "scripted_vehicle_list");

  py::class_<sim::pedestrian> walker(m, "pedestrian", "A pedestrian that replays its motion (a disc).");
  copied_by_value(with_fields(walker))
      .def_readwrite("name", &sim::pedestrian::name)
      .def_readwrite("motion", &sim::pedestrian::motion)
      .def_readwrite("radius", &sim::pedestrian::radius, "[m]");
  agent_list<sim::pedestrian>(m, "pedestrian_list");

  py::class_<sim::static_obstacle> still(m, "static_obstacle", "A convex polygon that never moves.");
  copied_by_value(with_fields(still))
      .def_readwrite("name", &sim::static_obstacle::name)
      .def_readwrite("vertices", &sim::static_obstacle::vertices, "world frame [m], 3 to 16, either orientation");
  agent_list<sim::static_obstacle>(m, "static_obstacle_list");
}

void bind_scenario(py::module_& m) {
  py::class_<sim::scenario> s(m, "scenario", "Everything a run needs (change it before the run starts).");
  with_keyword_constructor(copied_by_value(s))
      .def_readwrite("name", &sim::scenario::name)
      .def_readwrite("description", &sim::scenario::description)
      .def_readwrite("duration", &sim::scenario::duration, "[s]")
      .def_readwrite("time_step", &sim::scenario::time_step, "dt [s]")
      .def_readwrite("seed", &sim::scenario::seed, "seeds the sensor noise")
      .def_readwrite("noise", &sim::scenario::noise, "on every observation of a planning vehicle")
      .def_readwrite("planning_vehicles", &sim::scenario::planning_vehicles)
      .def_readwrite("scripted_vehicles", &sim::scenario::scripted_vehicles)
      .def_readwrite("pedestrians", &sim::scenario::pedestrians)
      .def_readwrite("static_obstacles", &sim::scenario::static_obstacles)
      .def_property(
          "drivable_area",
          [](const sim::scenario& sc) -> std::optional<std::shared_ptr<drivable_area>> {
            if (sc.drivable_area.empty()) return std::nullopt;
            return std::make_shared<drivable_area>(sc.drivable_area);
          },
          [](sim::scenario& sc, const std::optional<std::shared_ptr<drivable_area>>& area) {
            sc.drivable_area = area && *area ? drivable_outline{(*area)->polygons(), (*area)->open_edges()}
                                             : drivable_outline{};
          },
          "the road constraint of every planning vehicle (spec §5), or None")
      .def("validation_error", [](const sim::scenario& sc) { return sim::validation_error(sc); },
           "The first problem, naming the agent and the field, or None.")
      .def("__eq__", [](const sim::scenario& a, py::handle b) {
        return py::isinstance<sim::scenario>(b) && a == b.cast<const sim::scenario&>();
      })
      .def(py::pickle([](const sim::scenario& sc) { return scenario_file::scenario_text(sc); },
                      [](const std::string& text) { return scenario_file::load_text(text, "<pickled scenario>").scenario; }))
      .def("__repr__", [](const sim::scenario& sc) {
        return "scenario(name=" + py::repr(py::str(sc.name)).cast<std::string>() + ", " +
               std::to_string(sc.planning_vehicles.size()) + " planning vehicles, " +
               std::to_string(sc.scripted_vehicles.size()) + " scripted vehicles, " +
               std::to_string(sc.pedestrians.size()) + " pedestrians, " +
               std::to_string(sc.static_obstacles.size()) + " static obstacles)";
      });
  s.attr("__hash__") = py::none();
}

}  // namespace

void bind_scenario_values(py::module_& m) {
  bind_path(m);
  bind_motions(m);
  bind_agents(m);
  bind_scenario(m);
}

}  // namespace mm::python
