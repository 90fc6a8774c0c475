// movseg.Params: every field of movseg/params.def as an attribute; enum fields take and give
// their names ("homography").
#include <string>

#include "bindings.h"
#include "fields.h"
#include "movseg/params.h"

namespace py = pybind11;

namespace movseg::python {
namespace {

template <typename T>
void bindField(py::class_<Params>& cls, const std::string& name, T Params::*member) {
  const std::string doc = docOf(paramFields(), name);
  const auto get = [member](const Params& p) { return toPython(p.*member); };
  if constexpr (std::is_enum_v<T>) {
    cls.def_property(pythonName(name).c_str(), get,
                     [name](Params& p, const std::string& value) { setParam(&p, name, value); },
                     doc.c_str());
  } else {
    cls.def_property(pythonName(name).c_str(), get,
                     [member](Params& p, const T& value) { p.*member = value; }, doc.c_str());
  }
}

bool isField(const std::string& python_name) {
  for (const FieldInfo& field : paramFields()) {
    if (pythonName(field.name) == python_name) return true;
  }
  return false;
}

// Keyword arguments go through the attributes' setters, which convert and type-check them.
Params fromKeywords(const py::kwargs& values) {
  py::object params = py::cast(Params());
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    if (!isField(name)) {
      throw py::type_error("Params has no field '" + name + "'");
    }
    try {
      py::setattr(params, key, value);
    } catch (const py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError)) throw;
      throw py::type_error("Params." + name + " cannot be " + py::repr(value).cast<std::string>());
    }
  }
  return params.cast<Params>();
}

}  // namespace

void bindParams(py::module_& module) {
  py::class_<Params> params(module, "Params",
                            "Every parameter of the method (movseg/params.def); "
                            "Params(lambda_=500, static_camera=True) sets fields by name "
                            "(lambda is lambda_ in Python).");
  params.def(py::init(&fromKeywords))
      .def("check", &Params::check, "Raises ValueError naming the first parameter out of range.")
      .def("__eq__", [](const Params& a, const Params& b) { return a == b; }, py::is_operator())
      .def("__copy__", [](const Params& p) { return p; })
      .def("__deepcopy__", [](const Params& p, const py::dict&) { return p; }, py::arg("memo"))
      .def("__repr__", [](const py::object& p) { return reprOf(p, "Params", paramFields()); });
#define MOVSEG_PARAM(type, name, default_value, min, max, step, unit, doc) \
  bindField<type>(params, #name, &Params::name);
#include "movseg/params.def"
#undef MOVSEG_PARAM
}

}  // namespace movseg::python
