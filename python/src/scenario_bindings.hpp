#pragma once

#include <pybind11/pybind11.h>

#include <vector>

#include "mm/sim/scenario.hpp"

// The scenario's lists of agents are list-like views that Python fills in place
// (`scenario.scripted_vehicles.append(b)`), in every translation unit that binds them.
PYBIND11_MAKE_OPAQUE(std::vector<mm::sim::planning_vehicle>)
PYBIND11_MAKE_OPAQUE(std::vector<mm::sim::scripted_vehicle>)
PYBIND11_MAKE_OPAQUE(std::vector<mm::sim::pedestrian>)
PYBIND11_MAKE_OPAQUE(std::vector<mm::sim::static_obstacle>)

namespace mm::python {

namespace py = pybind11;

/// The simulator's scenario and everything in it, to build or change in Python (`mm::sim::scenario`,
/// its agents, their paths, speed profiles and stops, the followers and the sensing noise), into `m`.
void bind_scenario_values(py::module_& m);

}  // namespace mm::python
