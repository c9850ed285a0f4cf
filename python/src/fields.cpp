#include "fields.hpp"

#include <pybind11/numpy.h>

namespace mm::python {

std::vector<std::string> field_names(py::handle type, bool writable_only) {
  std::vector<std::string> names;
  const py::handle property_type(reinterpret_cast<PyObject*>(&PyProperty_Type));
  // The class namespace is a read-only mapping proxy: copied into a dict to be walked in order.
  for (const auto& item : py::dict(type.attr("__dict__"))) {
    if (!py::isinstance(item.second, property_type)) continue;
    if (writable_only && item.second.attr("fset").is_none()) continue;
    names.push_back(py::str(item.first));
  }
  return names;
}

void set_fields(py::handle self, const py::kwargs& fields) {
  const py::handle type = py::type::of(self);
  const std::vector<std::string> names = field_names(type, true);
  for (const auto& item : fields) {
    const std::string name = py::str(item.first);
    bool known = false;
    for (const std::string& field : names) known = known || field == name;
    if (!known) {
      std::string list;
      for (const std::string& field : names) list += (list.empty() ? "" : ", ") + field;
      throw py::type_error(py::str(type.attr("__name__")).cast<std::string>() + " has no field '" + name +
                           "'; its fields are: " + list);
    }
    self.attr(name.c_str()) = item.second;
  }
}

std::string fields_repr(py::handle self, bool writable_only) {
  const py::handle type = py::type::of(self);
  std::string text = py::str(type.attr("__name__")).cast<std::string>() + "(";
  bool first = true;
  for (const std::string& name : field_names(type, writable_only)) {
    text += (first ? "" : ", ") + name + "=" + py::repr(self.attr(name.c_str())).cast<std::string>();
    first = false;
  }
  return text + ")";
}

py::array_t<bool> flags_of(const std::vector<std::uint8_t>& flags) {
  py::array_t<bool> out(static_cast<py::ssize_t>(flags.size()));
  bool* data = out.mutable_data();
  for (std::size_t i = 0; i < flags.size(); ++i) data[i] = flags[i] != 0;
  return out;
}

py::array_t<double> points_of(const std::vector<vec2>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    view(static_cast<py::ssize_t>(i), 0) = points[i].x;
    view(static_cast<py::ssize_t>(i), 1) = points[i].y;
  }
  return out;
}

}  // namespace mm::python
