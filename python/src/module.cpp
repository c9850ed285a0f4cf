// The extension module behind the `maneuvermap` package (docs/python.md).
#include "bindings.hpp"

PYBIND11_MODULE(_maneuvermap, m) {
  m.doc() = "Collision-avoidance motion planning with Maneuverability Maps (C++ core, pybind11 bindings)";
  m.attr("__version__") = MM_VERSION;
  mm::python::bind_core(m);
  pybind11::module_ sim = m.def_submodule("sim", "The traffic microsimulator and its scenario files");
  mm::python::bind_sim(sim);
  mm::python::bind_sweeps(sim);
  pybind11::module_ commonroad =
      m.def_submodule("commonroad", "Reading CommonRoad recordings and measuring their road users' room to maneuver");
  mm::python::bind_commonroad(commonroad);
}
