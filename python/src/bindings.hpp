#pragma once

#include <pybind11/pybind11.h>

namespace mm::python {

namespace py = pybind11;

/// The planner (`mm`): value types, `plan`, `planner`, `plan_reference` and the motion models.
void bind_core(py::module_& m);

/// The simulator and the scenario files (`mm::sim`, `mm::scenario_file`), into `m`.
void bind_sim(py::module_& m);

/// The parameter sweeps (`mm::cli::run_sweep`: `write_sweep`, `sweep_record`), into `m`; after `bind_sim`,
/// whose run metrics they hold.
void bind_sweeps(py::module_& m);

/// The CommonRoad reader and measurement (`mm::commonroad`), into `m`.
void bind_commonroad(py::module_& m);

}  // namespace mm::python
