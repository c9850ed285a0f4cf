// The extension module behind the `maneuvermap` package (docs/python.md).
#include "bindings.hpp"

#include <filesystem>
#include <string>

PYBIND11_MODULE(_maneuvermap, m) {
  // A file or directory that cannot be written is an OSError (its subclass by errno:
  // FileNotFoundError, NotADirectoryError, PermissionError), with the errno, the reason and the path.
  pybind11::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const std::filesystem::filesystem_error& e) {
      const pybind11::object error = pybind11::reinterpret_borrow<pybind11::object>(PyExc_OSError)(
          e.code().value(), std::string(e.what()), e.path1().string());
      PyErr_SetObject(PyExc_OSError, error.ptr());
    }
  });
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
