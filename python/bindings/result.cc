// movseg.Result and movseg.Diagnostics: what Segmenter.process returns, as numpy arrays and
// plain Python values. Diagnostics has one attribute per field of movseg/diagnostics.def.
#include <pybind11/stl.h>

#include "bindings.h"
#include "fields.h"
#include "movseg/segmenter.h"
#include "ndarray.h"

namespace py = pybind11;

namespace movseg::python {
namespace {

// Rows of (x, y, label) with label 0 = background, 1 = foreground, 2 = unknown.
py::array_t<float> featureArray(const std::vector<Feature>& features) {
  py::array_t<float> array({static_cast<py::ssize_t>(features.size()), py::ssize_t{3}});
  auto out = array.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < out.shape(0); ++i) {
    const Feature& f = features[static_cast<size_t>(i)];
    out(i, 0) = f.position.x;
    out(i, 1) = f.position.y;
    out(i, 2) = static_cast<float>(f.label);
  }
  return array;
}

py::dict debugDict(const std::map<std::string, cv::Mat>& pictures) {
  py::dict out;
  for (const auto& [name, picture] : pictures) out[py::str(name)] = arrayFromMat(picture);
  return out;
}

template <typename T>
void bindField(py::class_<Diagnostics>& cls, const std::string& name, T Diagnostics::*member) {
  const std::string doc = docOf(diagnosticFields(), name);
  cls.def_property_readonly(
      pythonName(name).c_str(), [member](const Diagnostics& d) { return toPython(d.*member); },
      doc.c_str());
}

void bindDiagnostics(py::module_& module) {
  py::class_<Diagnostics> diagnostics(module, "Diagnostics",
                                      "What happened while processing one frame "
                                      "(movseg/diagnostics.def).");
  diagnostics.def("__repr__",
                  [](const py::object& d) { return reprOf(d, "Diagnostics", diagnosticFields()); });
#define MOVSEG_DIAGNOSTIC(type, name, default_value, unit, doc) \
  bindField<type>(diagnostics, #name, &Diagnostics::name);
#include "movseg/diagnostics.def"
#undef MOVSEG_DIAGNOSTIC
}

}  // namespace

void bindResult(py::module_& module) {
  bindDiagnostics(module);
  py::class_<Result>(module, "Result", "The segmentation of one frame (see movseg/segmenter.h).")
      .def_property_readonly("mask", [](const Result& r) { return arrayFromMat(r.mask); },
                             "HxW uint8 array, 255 where something moves, else 0")
      .def_property_readonly("features", [](const Result& r) { return featureArray(r.features); },
                             "Nx3 float32 rows (x, y, label): 0 background, 1 foreground, "
                             "2 unknown")
      .def_readonly("diagnostics", &Result::diagnostics, "what happened (movseg.Diagnostics)")
      .def_property_readonly("debug", [](const Result& r) { return debugDict(r.debug); },
                             "each stage's picture by name, when Params.debug_images is set")
      .def("__repr__", [](const Result& r) {
        return "movseg.Result(mask " + std::to_string(r.mask.cols) + "x" +
               std::to_string(r.mask.rows) + ", " + std::to_string(cv::countNonZero(r.mask)) +
               " moving pixels, " + std::to_string(r.features.size()) + " features)";
      });
}

}  // namespace movseg::python
