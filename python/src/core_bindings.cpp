// Bindings of the core library: the planner's value types in, its result out (docs/python.md).
#include <pybind11/stl.h>
#include <pybind11/stl_bind.h>

#include <cmath>
#include <memory>
#include <optional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "fields.hpp"
#include "mm/input_bounds.hpp"
#include "mm/planner.hpp"
#include "mm/road_constraint.hpp"
#include "mm/reference_planner.hpp"
#include "mm/scenario_file/loader.hpp"

namespace mm::python {

namespace {

vec2 vec2_of(const py::sequence& xy) {
  if (py::isinstance<py::str>(xy) || py::len(xy) != 2) {
    throw py::value_error("a point needs two coordinates (x, y), got " + py::repr(xy).cast<std::string>());
  }
  return {xy[0].cast<double>(), xy[1].cast<double>()};
}

/// A kept `mm::planner`, which holds a cache: Python threads that share one take turns.
struct locked_planner {
  planner kept;
  std::mutex turn;
};

// The planning calls copy their input while they hold the GIL and plan on the copy without it: other
// Python threads run meanwhile, and may even change the input they passed.

/// `plan` and `planner.plan` raise on invalid input instead of returning its status.
plan_result checked(plan_result result) {
  if (!result.ok()) throw py::value_error(result.error);
  return result;
}

void bind_geometry(py::module_& m) {
  py::class_<vec2> point(m, "vec2", "A point or vector [m] in the world frame (x east, y north).");
  with_fields(point)
      .def(py::init([](double x, double y) { return vec2{x, y}; }), py::arg("x"), py::arg("y"))
      .def(py::init(&vec2_of), py::arg("xy"), "From any pair, e.g. a tuple (x, y).")
      .def_readwrite("x", &vec2::x, "[m]")
      .def_readwrite("y", &vec2::y, "[m]")
      .def("__iter__", [](const vec2& v) { return py::iter(py::make_tuple(v.x, v.y)); })
      .def("__len__", [](const vec2&) { return 2; });
  py::implicitly_convertible<py::tuple, vec2>();
  py::implicitly_convertible<py::list, vec2>();

  py::class_<pose> p(m, "pose", "A reference point [m] and a heading [rad], counter-clockwise from +x.");
  with_fields(p)
      .def(py::init([](double x, double y, double heading) { return pose{{x, y}, heading}; }), py::arg("x"),
           py::arg("y"), py::arg("heading") = 0.0)
      .def(py::init([](vec2 position, double heading) { return pose{position, heading}; }), py::arg("position"),
           py::arg("heading") = 0.0)
      .def_readwrite("position", &pose::position, "[m]")
      .def_readwrite("heading", &pose::heading, "[rad]")
      .def_property_readonly("x", [](const pose& q) { return q.position.x; })
      .def_property_readonly("y", [](const pose& q) { return q.position.y; });

  py::class_<rectangle> r(m, "rectangle", "Rectangle centred on the reference point (spec §2) [m].");
  with_fields(r)
      .def(py::init([](double length, double width) { return rectangle{length, width}; }), py::arg("length"),
           py::arg("width"))
      .def_readwrite("length", &rectangle::length, "along the heading [m]")
      .def_readwrite("width", &rectangle::width, "across [m]");
  py::class_<disc> d(m, "disc", "Disc centred on the reference point (pedestrians, spec §2) [m].");
  with_fields(d)
      .def(py::init([](double radius) { return disc{radius}; }), py::arg("radius"))
      .def_readwrite("radius", &disc::radius, "[m]");
  py::class_<convex_polygon> c(m, "convex_polygon", "Convex polygon in the body frame (x forward, y left) [m].");
  with_fields(c)
      .def(py::init([](std::vector<vec2> vertices) { return convex_polygon{std::move(vertices)}; }),
           py::arg("vertices"))
      .def_readwrite("vertices", &convex_polygon::vertices, "3 to 16 vertices, either orientation [m]");
  m.def("footprint_error", &footprint_error, py::arg("shape"),
        "Why `shape` is not a valid footprint, or None.");
}

void bind_motion(py::module_& m) {
  py::class_<ego_limits> l(m, "ego_limits", "Limits of the ego vehicle (spec §3).");
  with_fields(l)
      .def_readwrite("max_acceleration", &ego_limits::max_acceleration, "a_max [m/s²]")
      .def_readwrite("max_deceleration", &ego_limits::max_deceleration, "d_max [m/s²], positive")
      .def_readwrite("max_lateral_acceleration", &ego_limits::max_lateral_acceleration, "a_lat_max [m/s²]")
      .def_readwrite("min_turning_radius", &ego_limits::min_turning_radius, "R_min [m]")
      .def_readwrite("speed_cap", &ego_limits::speed_cap, "v_cap [m/s]")
      .def_readwrite("steering", &ego_limits::steering, "False: κ_max = 0 (the one-dimensional case)");

  py::class_<ego_state> e(m, "ego_state", "The ego vehicle as the planner sees it.");
  with_fields(e)
      .def_readwrite("pose", &ego_state::pose, "reference point [m] and heading [rad]")
      .def_readwrite("speed", &ego_state::speed, "v0 [m/s], 0 ≤ v0 ≤ v_cap")
      .def_readwrite("shape", &ego_state::shape, "footprint (default 4.5 m × 1.8 m); assign a whole shape")
      .def_readwrite("limits", &ego_state::limits);

  py::class_<maneuver> u(m, "maneuver", "u = (a, κ): constant acceleration [m/s²] and curvature [1/m] (spec §3).");
  with_fields(u)
      .def(py::init([](double a, double kappa) { return maneuver{a, kappa}; }), py::arg("acceleration"),
           py::arg("curvature") = 0.0)
      .def_readwrite("acceleration", &maneuver::acceleration, "[m/s²]")
      .def_readwrite("curvature", &maneuver::curvature, "[1/m], positive to the left");

  py::enum_<obstacle_kind>(m, "obstacle_kind")
      .value("vehicle", obstacle_kind::vehicle)
      .value("pedestrian", obstacle_kind::pedestrian)
      .value("static_obstacle", obstacle_kind::static_obstacle);

  py::class_<observation> o(m, "observation", "One observation of an obstacle.");
  with_fields(o)
      .def(py::init([](double time, pose where, double speed) { return observation{time, where, speed}; }),
           py::arg("time"), py::arg("pose"), py::arg("speed"))
      .def_readwrite("time", &observation::time, "[s]")
      .def_readwrite("pose", &observation::pose)
      .def_readwrite("speed", &observation::speed, "[m/s]");
  auto observations = py::bind_vector<std::vector<observation>>(m, "observation_list");
  compared_by_elements(observations);
  py::implicitly_convertible<py::list, std::vector<observation>>();
  py::implicitly_convertible<py::tuple, std::vector<observation>>();

  py::class_<motion_estimate> me(m, "motion_estimate", "An obstacle's motion at the planning time (spec §4).");
  with_fields(me)
      .def_readwrite("pose", &motion_estimate::pose)
      .def_readwrite("speed", &motion_estimate::speed, "v_j [m/s] ≥ 0")
      .def_readwrite("yaw_rate", &motion_estimate::yaw_rate, "ω_j [rad/s], counter-clockwise positive");

  py::class_<obstacle_track> t(m, "obstacle_track",
                               "An observed obstacle: footprint and observations, oldest first (spec §4).");
  with_fields(t)
      .def_readwrite("id", &obstacle_track::id)
      .def_readwrite("kind", &obstacle_track::kind)
      .def_readwrite("shape", &obstacle_track::shape, "assign a whole shape")
      .def_readwrite("history", &obstacle_track::history, "observations, strictly increasing times")
      .def_readwrite("motion", &obstacle_track::motion,
                     "the motion at the planning time when already estimated; None: estimated from the history");
  auto tracks = py::bind_vector<std::vector<obstacle_track>>(m, "obstacle_track_list");
  compared_by_elements(tracks);
  py::implicitly_convertible<py::list, std::vector<obstacle_track>>();
  py::implicitly_convertible<py::tuple, std::vector<obstacle_track>>();

  m.def("max_curvature", &max_curvature, py::arg("speed"), py::arg("limits"),
        "κ_max(v) = min(1/R_min, a_lat_max/v²) [1/m] (spec §3).");
  m.def("maneuver_pose", &maneuver_pose, py::arg("start"), py::arg("initial_speed"), py::arg("maneuver"),
        py::arg("t"), py::arg("horizon"), py::arg("speed_cap"),
        "The ego's pose at time t [s] executing the maneuver: its arc until `horizon`, then straight (spec §5).");
  m.def("estimate_motion", &estimate_motion, py::arg("track"), py::arg("history_window"), py::arg("now"),
        "Least-squares speed and yaw rate over the history window, propagated to `now` (spec §4).");
  m.def("forecast_pose", &forecast_pose, py::arg("motion"), py::arg("forecast_time"), py::arg("t"),
        "Forecast pose at time t ≥ 0: CTRV until the forecast time τ, straight after (spec §4).");
}

void bind_config(py::module_& m) {
  py::enum_<forecast_policy_kind>(m, "forecast_policy_kind")
      .value("adjustable", forecast_policy_kind::adjustable)
      .value("constant", forecast_policy_kind::constant)
      .value("robust", forecast_policy_kind::robust);
  py::class_<forecast_policy> f(m, "forecast_policy",
                                "ADJ, a constant forecast time τ (spec §7), or robust (docs/method.md).");
  with_fields(f)
      .def_readwrite("kind", &forecast_policy::kind)
      .def_readwrite("constant_forecast_time", &forecast_policy::constant_forecast_time,
                     "τ [s] of the constant policy, on the forecast grid")
      .def_static("parse", [](const std::string& text) {
            const auto policy = scenario_file::parse_policy(text);
            if (!policy) throw py::value_error("forecast policy '" + text + "': expected " + std::string(scenario_file::policy_forms));
            return *policy;
          }, py::arg("text"), "From `adj`, `const:SECONDS` or `robust`, as on the command line.")
      .def("__str__", [](const forecast_policy& policy) { return scenario_file::policy_name(policy); });

  py::class_<effort_weights> w(m, "effort_weights", "w_lon, w_lat of the effort J (spec §8) [s⁴/m²].");
  with_fields(w)
      .def_readwrite("longitudinal", &effort_weights::longitudinal)
      .def_readwrite("lateral", &effort_weights::lateral);
  py::class_<sampling_resolution> s(m, "sampling_resolution", "Samples per family: accelerations × curvatures.");
  with_fields(s)
      .def_readwrite("accelerations", &sampling_resolution::accelerations, "≥ 2")
      .def_readwrite("curvatures", &sampling_resolution::curvatures, "≥ 1");
  py::enum_<assignment_search_kind>(m, "assignment_search_kind")
      .value("coordinate_ascent", assignment_search_kind::coordinate_ascent)
      .value("exhaustive", assignment_search_kind::exhaustive);

  py::class_<planner_config> c(m, "planner_config", "Everything the planner can be told, with the spec's defaults.");
  with_fields(c)
      .def_readwrite("displacement_horizon", &planner_config::displacement_horizon, "T_h [s] (spec §3)")
      .def_readwrite("collision_window", &planner_config::collision_window, "T_c [s] (spec §5)")
      .def_readwrite("forecast_step", &planner_config::forecast_step, "Δτ [s] (spec §4)")
      .def_readwrite("forecast_count", &planner_config::forecast_count, "τ_i = i·Δτ, i = 0..count−1")
      .def_readwrite("history_window", &planner_config::history_window, "H [s] (spec §4)")
      .def_readwrite("safety_margin", &planner_config::safety_margin, "inflation of every obstacle [m] (spec §2)")
      .def_readwrite("policy", &planner_config::policy)
      .def_readwrite("effort", &planner_config::effort)
      .def_readwrite("urgent_steering", &planner_config::urgent_steering, "spec §8.3")
      .def_readwrite("resolution", &planner_config::resolution)
      .def_readwrite("max_time_step", &planner_config::max_time_step, "upper bound of the collision time step [s]")
      .def_readwrite("assignment_search", &planner_config::assignment_search, "spec §9")
      .def_readwrite("max_exhaustive_assignments", &planner_config::max_exhaustive_assignments)
      .def_readwrite("record_samples", &planner_config::record_samples, "fill plan_result.samples")
      .def_readwrite("map_column", &planner_config::map_column,
                     "compute every forecast time's indices (False: only those the decision reads)")
      .def_readwrite("decision_only", &planner_config::decision_only,
                     "without the map column: a step whose u_nom is proven safe under every forecast time returns "
                     "it without any index (plan_result.indices_computed False); the same command");
  m.def("forecast_times", &forecast_times, py::arg("config"), "The forecast grid τ_i = i·Δτ [s] (spec §4).");

  py::class_<drivable_area, std::shared_ptr<drivable_area>> area(
      m, "drivable_area",
      "The drivable area of spec §5's road constraint: the union of polygons [m], and the edges of theirs that "
      "lead on beyond the map (never boundary). Immutable; one area serves many planning inputs.");
  area.def(py::init([](const std::vector<std::vector<vec2>>& polygons,
                       const std::vector<std::pair<std::size_t, std::size_t>>& open_edges) {
             std::vector<polygon_edge> edges;
             for (const auto& [polygon, edge] : open_edges) edges.push_back({polygon, edge});
             if (auto error = drivable_area_error(polygons, edges)) throw py::value_error("drivable area: " + *error);
             return std::make_shared<drivable_area>(polygons, edges);
           }),
           py::arg("polygons"), py::arg("open_edges") = std::vector<std::pair<std::size_t, std::size_t>>{},
           "From polygons (each a sequence of (x, y) [m], at least 3) and open edges ((polygon, edge) pairs, edge j "
           "from vertex j to the next). ValueError naming the polygon and vertex when they cannot be one.")
      .def_property_readonly("polygons", [](const drivable_area& a) {
        py::list out;
        for (const std::vector<vec2>& p : a.polygons()) out.append(points_of(p));
        return out;
      }, "each an array of shape (vertices, 2) [m]")
      .def_property_readonly("open_edges", [](const drivable_area& a) {
        std::vector<std::pair<std::size_t, std::size_t>> edges;
        for (const polygon_edge& e : a.open_edges()) edges.emplace_back(e.polygon, e.edge);
        return edges;
      }, "(polygon, edge) pairs")
      .def_property_readonly("boundary", [](const drivable_area& a) {
        py::array_t<double> out({static_cast<py::ssize_t>(a.boundary().size()), py::ssize_t{2}, py::ssize_t{2}});
        auto view = out.mutable_unchecked<3>();
        for (py::ssize_t i = 0; i < view.shape(0); ++i) {
          const segment& e = a.boundary()[static_cast<std::size_t>(i)];
          view(i, 0, 0) = e.a.x;
          view(i, 0, 1) = e.a.y;
          view(i, 1, 0) = e.b.x;
          view(i, 1, 1) = e.b.y;
        }
        return out;
      }, "the segments of the union's boundary, shape (segments, 2 ends, 2) [m]")
      .def("contains", &drivable_area::contains, py::arg("point"), "True when the point lies in one of the polygons.")
      .def("__eq__", [](const drivable_area& a, py::handle other) {
        if (!py::isinstance<drivable_area>(other)) return false;
        const auto& b = other.cast<const drivable_area&>();
        return a.polygons() == b.polygons() && a.open_edges() == b.open_edges();
      })
      .def("__repr__", [](const drivable_area& a) {
        return "drivable_area(" + std::to_string(a.polygons().size()) + " polygons, " +
               std::to_string(a.boundary().size()) + " boundary segments)";
      })
      .def(py::pickle([](const drivable_area& a) {
             std::vector<std::pair<std::size_t, std::size_t>> edges;
             for (const polygon_edge& e : a.open_edges()) edges.emplace_back(e.polygon, e.edge);
             return py::make_tuple(a.polygons(), edges);
           },
           [](const py::tuple& state) {
             std::vector<polygon_edge> edges;
             for (const auto& [polygon, edge] : state[1].cast<std::vector<std::pair<std::size_t, std::size_t>>>()) {
               edges.push_back({polygon, edge});
             }
             return std::make_shared<drivable_area>(state[0].cast<std::vector<std::vector<vec2>>>(), edges);
           }));
  area.attr("__hash__") = py::none();
  m.def("starts_on_drivable_area", &starts_on_drivable_area, py::arg("area"), py::arg("ego"),
        "True when the road constraint binds the ego: its reference point in the area, its footprint clear of the "
        "boundary (spec §5).");

  py::class_<plan_input> in(m, "plan_input", "One planning step: the ego, u_nom and the observed obstacles.");
  with_fields(in)
      .def_readwrite("time", &plan_input::time, "planning time [s]; no observation may be later")
      .def_readwrite("ego", &plan_input::ego)
      .def_readwrite("nominal", &plan_input::nominal, "u_nom (spec §8)")
      .def_readwrite("obstacles", &plan_input::obstacles)
      .def_readwrite("config", &plan_input::config)
      .def_property(
          "drivable_area",
          [](const plan_input& i) -> std::optional<std::shared_ptr<drivable_area>> {
            if (!i.drivable_area) return std::nullopt;
            return std::const_pointer_cast<drivable_area>(i.drivable_area);
          },
          [](plan_input& i, std::optional<std::shared_ptr<drivable_area>> given) {
            i.drivable_area = given ? std::move(*given) : nullptr;
          },
          "the road constraint (spec §5): a maneuver that leaves this area within T_h is unsafe; None: none");
}

void bind_result(py::module_& m) {
  py::enum_<plan_status>(m, "plan_status")
      .value("ok", plan_status::ok)
      .value("invalid_input", plan_status::invalid_input);
  py::enum_<family>(m, "family")
      .value("brake", family::brake)
      .value("accelerate", family::accelerate);
  py::enum_<planning_mode>(m, "planning_mode")
      .value("nominal", planning_mode::nominal)
      .value("avoid", planning_mode::avoid)
      .value("urgent", planning_mode::urgent)
      .value("near_crash", planning_mode::near_crash);

  py::class_<obstacle_assessment> oa(m, "obstacle_assessment", "How the planner saw one obstacle.");
  pickled_by_members(oa, &obstacle_assessment::id, &obstacle_assessment::relevant, &obstacle_assessment::motion,
                     &obstacle_assessment::time_to_collision, &obstacle_assessment::forecast_index);
  oa.def_readonly("id", &obstacle_assessment::id)
      .def_readonly("relevant", &obstacle_assessment::relevant, "False: too far to reach within T_c (spec §9)")
      .def_readonly("motion", &obstacle_assessment::motion)
      .def_readonly("time_to_collision", &obstacle_assessment::time_to_collision, "[s], inf for none")
      .def_readonly("forecast_index", &obstacle_assessment::forecast_index, "its forecast time (spec §9)")
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<plan_work> pw(m, "plan_work", "How much collision work the step did (docs/performance.md).");
  pickled_by_members(pw, &plan_work::relevant_obstacles, &plan_work::bound_checks, &plan_work::distance_evaluations,
                     &plan_work::refinements, &plan_work::translation_minima, &plan_work::assignments_evaluated);
  pw.def_readonly("relevant_obstacles", &plan_work::relevant_obstacles)
      .def_readonly("bound_checks", &plan_work::bound_checks)
      .def_readonly("distance_evaluations", &plan_work::distance_evaluations)
      .def_readonly("refinements", &plan_work::refinements)
      .def_readonly("translation_minima", &plan_work::translation_minima)
      .def_readonly("assignments_evaluated", &plan_work::assignments_evaluated)
      .def("__repr__", [](py::handle self) { return fields_repr(self); });

  py::class_<sample_snapshot> ss(
      m, "sample_snapshot", "The sampled maneuvers of a step and their safety (plan_input.config.record_samples).");
  pickled_by_members(ss, &sample_snapshot::maneuvers, &sample_snapshot::families, &sample_snapshot::end_points,
                     &sample_snapshot::area_weights, &sample_snapshot::on_nominal_curvature,
                     &sample_snapshot::safe_by_forecast, &sample_snapshot::safe_selected);
  ss.def_property_readonly("accelerations", [](const sample_snapshot& s) {
        std::vector<double> a;
        for (const maneuver& u : s.maneuvers) a.push_back(u.acceleration);
        return array_of(a);
      }, "a of every sample [m/s²]")
      .def_property_readonly("curvatures", [](const sample_snapshot& s) {
        std::vector<double> k;
        for (const maneuver& u : s.maneuvers) k.push_back(u.curvature);
        return array_of(k);
      }, "κ of every sample [1/m]")
      .def_property_readonly("families", [](const sample_snapshot& s) { return s.families; })
      .def_property_readonly("end_points", [](const sample_snapshot& s) { return points_of(s.end_points); },
                             "the displacements, world frame [m], shape (samples, 2)")
      .def_property_readonly("area_weights", [](const sample_snapshot& s) { return array_of(s.area_weights); },
                             "[m²]; 0 on the nominal-curvature columns")
      .def_property_readonly("on_nominal_curvature",
                             [](const sample_snapshot& s) { return flags_of(s.on_nominal_curvature); })
      .def_property_readonly("safe_by_forecast", [](const sample_snapshot& s) {
        const auto rows = static_cast<py::ssize_t>(s.safe_by_forecast.size());
        const auto columns = static_cast<py::ssize_t>(s.maneuvers.size());
        py::array_t<bool> out({rows, columns});
        auto view = out.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < rows; ++i) {
          for (py::ssize_t k = 0; k < columns; ++k) {
            view(i, k) = s.safe_by_forecast[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] != 0;
          }
        }
        return out;
      }, "[i, m]: sample m is safe with every obstacle forecast with τ_i, shape (forecast times, samples)")
      .def_property_readonly("safe_selected", [](const sample_snapshot& s) { return flags_of(s.safe_selected); },
                             "safe under the selected forecast times");

  py::class_<plan_result> pr(m, "plan_result", "Everything one planning step computes (spec §6–§9).");
  pickled_by_members(pr, &plan_result::status, &plan_result::error, &plan_result::command, &plan_result::mode,
                     &plan_result::selected_family, &plan_result::forecast_time, &plan_result::forecast_index,
                     &plan_result::mi_brake_selected, &plan_result::mi_accelerate_selected, &plan_result::robust,
                     &plan_result::on_drivable_area, &plan_result::indices_computed,
                     &plan_result::forecast_times, &plan_result::mi_brake, &plan_result::mi_accelerate,
                     &plan_result::excluded, &plan_result::time_to_collision, &plan_result::collision_time_step,
                     &plan_result::obstacles, &plan_result::samples, &plan_result::work);
  pr.def_readonly("status", &plan_result::status)
      .def_readonly("error", &plan_result::error)
      .def_readonly("command", &plan_result::command, "the chosen u")
      .def_readonly("mode", &plan_result::mode, "which rule of spec §8 chose it")
      .def_readonly("selected_family", &plan_result::selected_family, "spec §7")
      .def_readonly("robust", &plan_result::robust,
                    "robust policy: the command is safe under every non-excluded forecast time (else ADJ decided)")
      .def_readonly("on_drivable_area", &plan_result::on_drivable_area,
                    "the input's drivable area constrained this step (given, and the ego started on it)")
      .def_readonly("indices_computed", &plan_result::indices_computed,
                    "False when config.decision_only returned u_nom without the indices: τ̄, the family and the "
                    "selected indices then hold their defaults")
      .def_readonly("forecast_time", &plan_result::forecast_time, "τ̄ [s]")
      .def_readonly("forecast_index", &plan_result::forecast_index, "ī")
      .def_readonly("mi_brake_selected", &plan_result::mi_brake_selected, "MI− under the selected forecast times")
      .def_readonly("mi_accelerate_selected", &plan_result::mi_accelerate_selected,
                    "MI+ under the selected forecast times")
      .def_property_readonly("forecast_times", [](const plan_result& r) { return array_of(r.forecast_times); },
                             "τ_i [s]: the map column's rows")
      .def_property_readonly("mi_brake", [](const plan_result& r) { return array_of(r.mi_brake); },
                             "MI−(τ_i): the map column (spec §6); empty when config.map_column is False")
      .def_property_readonly("mi_accelerate", [](const plan_result& r) { return array_of(r.mi_accelerate); },
                             "MI+(τ_i)")
      .def_property_readonly("excluded", [](const plan_result& r) { return flags_of(r.excluded); }, "τ_i > TTC")
      .def_readonly("time_to_collision", &plan_result::time_to_collision, "TTC [s], inf for none (spec §6)")
      .def_readonly("collision_time_step", &plan_result::collision_time_step, "[s]")
      .def_readonly("obstacles", &plan_result::obstacles, "in input order")
      .def_readonly("samples", &plan_result::samples, "when config.record_samples, else None")
      .def_readonly("work", &plan_result::work)
      .def("ok", &plan_result::ok)
      .def("__repr__", [](const plan_result& r) {
        const auto number = [](double value) { return py::repr(py::float_(value)).cast<std::string>(); };
        return "plan_result(command=maneuver(acceleration=" + number(r.command.acceleration) +
               ", curvature=" + number(r.command.curvature) + "), mode=" + std::string(to_string(r.mode)) +
               ", selected_family=" + std::string(to_string(r.selected_family)) +
               ", forecast_time=" + number(r.forecast_time) +
               ", time_to_collision=" + number(r.time_to_collision) + ")";
      });
}

void bind_planning(py::module_& m) {
  m.def("validation_error", &validation_error, py::arg("input"),
        "Why the input cannot be planned on (the field, its value and what was expected), or None.");
  // The magnitudes validation_error accepts (mm/input_bounds.hpp), for callers that check their
  // inputs before planning.
  m.attr("largest_input_coordinate") = largest_input_coordinate;
  m.attr("largest_input_speed") = largest_input_speed;
  m.attr("largest_input_yaw_rate") = largest_input_yaw_rate;
  m.attr("largest_input_acceleration") = largest_input_acceleration;
  m.attr("smallest_input_turning_radius") = smallest_input_turning_radius;
  m.attr("largest_input_safety_margin") = largest_input_safety_margin;
  m.attr("largest_observation_age") = largest_observation_age;
  m.attr("largest_footprint_size") = largest_footprint_size;
  m.def("plan", [](const plan_input& input) {
          const plan_input own = input;
          const py::gil_scoped_release release;
          return checked(plan(own));
        }, py::arg("input"),
        "One planning step with Maneuverability Maps (spec §3–§9), the fast path. ValueError on invalid "
        "input, with the field, its value and what was expected. Releases the GIL.");

  py::class_<reference_resolution> rr(m, "reference_resolution", "Resolution of the reference planner.");
  with_fields(rr)
      .def_readwrite("sampling", &reference_resolution::sampling, "dense (a, κ) grid per family")
      .def_readwrite("proof_resolution", &reference_resolution::proof_resolution,
                     "time resolution of the continuous-time collision proof [s]")
      .def_readwrite("one_dimensional_accelerations", &reference_resolution::one_dimensional_accelerations,
                     "accelerations per family without steering (κ_max = 0): each family is a segment");
  m.def("plan_reference",
        [](const plan_input& input, const reference_resolution& resolution) {
          const plan_input own = input;
          const py::gil_scoped_release release;
          return checked(plan_reference(own, resolution));
        },
        py::arg("input"), py::arg("resolution") = reference_resolution{},
        "The slow, obviously-correct reference of plan (spec §11): seconds per step.");

  py::class_<locked_planner>(m, "planner",
                             "The planner of one vehicle's consecutive steps: plan(input) returns exactly what "
                             "maneuvermap.plan(input) returns, reusing what the previous call sampled (spec §11 "
                             "tests that). Calls from several threads take turns.")
      .def(py::init<>())
      .def("plan", [](locked_planner& p, const plan_input& input) {
            const plan_input own = input;
            const py::gil_scoped_release release;
            const std::lock_guard<std::mutex> hold(p.turn);
            return checked(p.kept.plan(own));
          }, py::arg("input"), "As maneuvermap.plan. Releases the GIL.");
}

}  // namespace

void bind_core(py::module_& m) {
  bind_geometry(m);
  bind_motion(m);
  bind_config(m);
  bind_result(m);
  bind_planning(m);
}

}  // namespace mm::python
