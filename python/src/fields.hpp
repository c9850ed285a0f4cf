#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mm/forecast.hpp"

// Lists that Python code fills in place (`input.obstacles.append(track)`) are bound as opaque
// list-like types with reference semantics; every other std::vector converts to a Python list.
PYBIND11_MAKE_OPAQUE(std::vector<mm::obstacle_track>)
PYBIND11_MAKE_OPAQUE(std::vector<mm::observation>)

namespace mm::python {

namespace py = pybind11;

/// The names of the fields (the properties) of a bound class, in the order they were bound; with
/// `writable_only`, those that can be set (a value type's own fields, not what is computed from them).
std::vector<std::string> field_names(py::handle type, bool writable_only = false);

/// Sets the fields of `self` from keyword arguments; a name that is not a field is a TypeError
/// that names it and lists the fields (unknown keys are errors, as in the scenario files).
void set_fields(py::handle self, const py::kwargs& fields);

/// `type_name(field=repr(value), ...)` over every field (every writable one with `writable_only`).
std::string fields_repr(py::handle self, bool writable_only = false);

/// Gives a bound value type a keyword constructor (`ego_state(speed=8.3)`): a name that is not a
/// field is a TypeError listing the fields (`set_fields`).
template <class T, class... Options>
py::class_<T, Options...>& with_keyword_constructor(py::class_<T, Options...>& c) {
  c.def(py::init<>());
  c.def(py::init([](const py::kwargs& fields) {
          py::object value = py::cast(T{});
          set_fields(value, fields);
          return value.cast<T>();
        }),
        "Every field from its keyword argument; the others keep their defaults.");
  return c;
}

/// Gives a bound type `__copy__` and `__deepcopy__` by its C++ copy (a deep copy: the C++ value owns
/// everything it holds) instead of a pickled round trip, for a scenario, its agents and paths, so that
/// `copy.deepcopy(loaded)` makes a variant to change while the original stays as it was (and a
/// loaded scenario, which does not pickle, copies too).
template <class T, class... Options>
py::class_<T, Options...>& copied_by_value(py::class_<T, Options...>& c) {
  c.def("__copy__", [](const T& self) { return T(self); });
  c.def("__deepcopy__", [](const T& self, const py::dict&) { return T(self); }, py::arg("memo"));
  return c;
}

/// `with_keyword_constructor`, `__repr__` and `__eq__` by fields (values compare equal when every
/// field does), and pickling by fields (so that values can be sent to other processes:
/// `multiprocessing`, `concurrent.futures`).
template <class T, class... Options>
py::class_<T, Options...>& with_fields(py::class_<T, Options...>& c) {
  with_keyword_constructor(c);
  c.def("__repr__", [](py::handle self) { return fields_repr(self, true); });
  c.def("__eq__", [](py::handle self, py::handle other) {
    if (!py::isinstance(other, py::type::of(self))) return false;
    for (const std::string& name : field_names(py::type::of(self), true)) {
      if (!self.attr(name.c_str()).equal(other.attr(name.c_str()))) return false;
    }
    return true;
  });
  c.attr("__hash__") = py::none();
  c.def(py::pickle(
      [](py::handle self) {
        py::dict state;
        for (const std::string& name : field_names(py::type::of(self), true)) {
          state[py::str(name)] = self.attr(name.c_str());
        }
        return state;
      },
      [](const py::dict& state) {
        py::object value = py::cast(T{});
        set_fields(value, py::reinterpret_borrow<py::kwargs>(state));
        return value.cast<T>();
      }));
  return c;
}

/// Gives a bound list type `__eq__` by its elements (a list of value types without a C++ `==`), so
/// that values holding such lists compare by their contents; the other side may be a Python list.
template <class Vector, class... Options>
py::class_<Vector, Options...>& equal_by_elements(py::class_<Vector, Options...>& c) {
  c.def("__eq__", [](py::handle self, py::handle other) {
    if (!py::isinstance<py::iterable>(other) || py::isinstance<py::str>(other)) return false;
    const auto as_list = [](py::handle items) { return py::list(py::reinterpret_borrow<py::object>(items)); };
    return as_list(self).equal(as_list(other));
  });
  c.attr("__hash__") = py::none();
  return c;
}

/// `equal_by_elements`, and pickled as the list of its elements.
template <class Vector, class... Options>
py::class_<Vector, Options...>& compared_by_elements(py::class_<Vector, Options...>& c) {
  equal_by_elements(c);
  c.def(py::pickle([](py::handle self) { return py::list(py::reinterpret_borrow<py::object>(self)); },
                   [](const py::list& items) {
                     Vector values;
                     for (py::handle item : items) values.push_back(item.cast<typename Vector::value_type>());
                     return values;
                   }));
  return c;
}

/// Pickling by C++ members, for a type that Python only reads (a result): its state is the tuple of
/// the Python values of `members`, each of which pickles (numbers, strings, lists, None, enums, and
/// the bound types that pickle by their fields or their members). Name every member: a member left
/// out comes back with its default (tests/python compares every attribute of a round trip).
template <class T, class... Options, class... Members>
py::class_<T, Options...>& pickled_by_members(py::class_<T, Options...>& c, Members T::*... members) {
  c.def(py::pickle([members...](const T& self) { return py::make_tuple(py::cast(self.*members)...); },
                   [members...](const py::tuple& state) {
                     if (state.size() != sizeof...(Members)) {
                       throw std::runtime_error("cannot unpickle: expected a state of " +
                                                std::to_string(sizeof...(Members)) + " members, got " +
                                                std::to_string(state.size()));
                     }
                     T value;
                     std::size_t i = 0;
                     ((value.*members = state[i++].template cast<Members>()), ...);
                     return value;
                   }));
  return c;
}

/// A copy of `values` as a one-dimensional NumPy array.
template <class T>
py::array_t<T> array_of(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  T* data = out.mutable_data();
  for (std::size_t i = 0; i < values.size(); ++i) data[i] = values[i];
  return out;
}

/// Points [m] as a NumPy array of shape (points, 2): x and y in the columns.
py::array_t<double> points_of(const std::vector<vec2>& points);

/// A copy of 0/1 flags as a one-dimensional NumPy array of bool.
py::array_t<bool> flags_of(const std::vector<std::uint8_t>& flags);

}  // namespace mm::python
