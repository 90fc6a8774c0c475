// movseg.Result and movseg.Diagnostics: what Segmenter.process returns, as numpy arrays and
// plain Python values.
#include <pybind11/stl.h>

#include "bindings.h"
#include "movseg/segmenter.h"
#include "ndarray.h"

namespace py = pybind11;

namespace movseg::python {
namespace {

py::array_t<double> modelArray(const cv::Matx33d& model, int rows) {
  py::array_t<double> array({rows, 3});
  auto out = array.mutable_unchecked<2>();
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = model(r, c);
  }
  return array;
}

// The first two rows of an affine model; None for a homography, which has no affine form.
py::object affineArray(const Diagnostics& d) {
  if (!d.model_is_affine) return py::none();
  return modelArray(d.model, 2);
}

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

py::dict timingDict(const Timings& t) {
  py::dict times;
  times["prepare_ms"] = t.prepare_ms;
  times["motion_ms"] = t.motion_ms;
  times["classify_ms"] = t.classify_ms;
  times["cut_ms"] = t.cut_ms;
  times["total_ms"] = t.total_ms;
  return times;
}

py::dict debugDict(const std::map<std::string, cv::Mat>& pictures) {
  py::dict out;
  for (const auto& [name, picture] : pictures) out[py::str(name)] = arrayFromMat(picture);
  return out;
}

void bindDiagnostics(py::module_& module) {
  py::class_<Diagnostics>(module, "Diagnostics", "What happened while processing one frame.")
      .def_property_readonly("model", [](const Diagnostics& d) { return modelArray(d.model, 3); },
                             "3x3 camera model, previous-frame to current-frame pixels")
      .def_readonly("model_is_affine", &Diagnostics::model_is_affine)
      .def_readonly("features", &Diagnostics::features, "feature points in the previous frame")
      .def_readonly("tracks", &Diagnostics::tracks, "features tracked forward and backward")
      .def_readonly("matches", &Diagnostics::matches, "tracks kept by the ZNCC and FB filters")
      .def_readonly("background_matches", &Diagnostics::background_matches)
      .def_readonly("foreground_matches", &Diagnostics::foreground_matches)
      .def_readonly("outer_iterations", &Diagnostics::outer_iterations)
      .def_readonly("foreground_seeds", &Diagnostics::foreground_seeds)
      .def_readonly("background_seeds", &Diagnostics::background_seeds)
      .def_readonly("unknown_seeds", &Diagnostics::unknown_seeds)
      .def_readonly("lambda_", &Diagnostics::lambda, "threshold of eq. (3) used for this pair")
      .def_readonly("cut_nodes", &Diagnostics::cut_nodes)
      .def_readonly("first_frame", &Diagnostics::first_frame)
      .def_readonly("reset", &Diagnostics::reset)
      .def_readonly("motion_fallback", &Diagnostics::motion_fallback)
      .def_readonly("no_background_seeds", &Diagnostics::no_background_seeds)
      .def_property_readonly("timings", [](const Diagnostics& d) { return timingDict(d.timings); });
}

}  // namespace

void bindResult(py::module_& module) {
  bindDiagnostics(module);
  py::class_<Result>(module, "Result", "The segmentation of one frame (see movseg/segmenter.h).")
      .def_property_readonly("mask", [](const Result& r) { return arrayFromMat(r.mask); },
                             "HxW uint8 array, 255 where something moves, else 0")
      .def_property_readonly("affine", [](const Result& r) { return affineArray(r.diagnostics); },
                             "2x3 affine camera model (float64), None for a homography")
      .def_property_readonly(
          "model", [](const Result& r) { return modelArray(r.diagnostics.model, 3); },
          "3x3 camera model (float64), previous-frame to current-frame pixels")
      .def_property_readonly("features", [](const Result& r) { return featureArray(r.features); },
                             "Nx3 float32 rows (x, y, label): 0 background, 1 foreground, "
                             "2 unknown")
      .def_property_readonly("timings",
                             [](const Result& r) { return timingDict(r.diagnostics.timings); },
                             "milliseconds per stage: prepare_ms, motion_ms, classify_ms, "
                             "cut_ms, total_ms")
      .def_readonly("diagnostics", &Result::diagnostics)
      .def_property_readonly("debug", [](const Result& r) { return debugDict(r.debug); },
                             "each stage's picture by name, when Params.debug_images is set");
}

}  // namespace movseg::python
