// movseg.Params: every field of movseg::Params, named and documented as in params.h (the field
// list is generated from that header; see python/gen_params_fields.py).
#include <set>
#include <string>

#include "bindings.h"
#include "movseg/params.h"

namespace py = pybind11;

namespace movseg::python {
namespace {

const std::set<std::string>& fieldNames() {
  static const std::set<std::string> names{
#define MOVSEG_PARAM(field, name, doc) name,
#include "params_fields.h"
#undef MOVSEG_PARAM
  };
  return names;
}

// Keyword arguments go through the attributes' setters, which convert and type-check them.
Params fromKeywords(const py::kwargs& values) {
  py::object params = py::cast(Params());
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    if (fieldNames().count(name) == 0) throw py::type_error("Params has no field '" + name + "'");
    try {
      py::setattr(params, key, value);
    } catch (const py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError)) throw;
      throw py::type_error("Params." + name + " cannot be " + py::repr(value).cast<std::string>());
    }
  }
  return params.cast<Params>();
}

std::string describe(const py::object& params) {
  std::string text = "movseg.Params(";
  const char* separator = "";
#define MOVSEG_PARAM(field, name, doc)                                                  \
  text += separator + std::string(name) + "=" + py::repr(params.attr(name)).cast<std::string>(); \
  separator = ", ";
#include "params_fields.h"
#undef MOVSEG_PARAM
  return text + ")";
}

}  // namespace

void bindParams(py::module_& module) {
  py::enum_<MotionModel>(module, "MotionModel", "The frame-to-frame camera model of §3.1.")
      .value("affine", MotionModel::kAffine)
      .value("homography", MotionModel::kHomography);

  py::class_<Params> params(module, "Params",
                            "Every parameter of the method; Params(lambda_=500, "
                            "static_camera=True) sets fields by name (lambda is lambda_ in "
                            "Python).");
  params.def(py::init(&fromKeywords))
      .def("check", &Params::check, "Raises ValueError naming the first parameter out of range.")
      .def("__repr__", &describe);
#define MOVSEG_PARAM(field, name, doc) params.def_readwrite(name, &Params::field, doc);
#include "params_fields.h"
#undef MOVSEG_PARAM
}

}  // namespace movseg::python
