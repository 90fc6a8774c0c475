// movseg.Segmenter, and movseg.createMovingCameraSubtractor for code written for cv2's MOG2.
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "bindings.h"
#include "movseg/background_subtractor.h"
#include "movseg/segmenter.h"
#include "ndarray.h"

namespace py = pybind11;

namespace movseg::python {
namespace {

// Calls run without the GIL, so that segmenters of different streams work in parallel Python
// threads; calls on one object still run one at a time. The GIL goes first, then the lock:
// a thread waiting for the lock never holds the GIL the running call may need (to release a
// numpy frame).
template <typename Object>
struct Guarded {
  explicit Guarded(Object guarded) : object(std::move(guarded)) {}
  template <typename Function>
  auto run(Function&& function) {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex);
    return function(object);
  }
  Object object;
  std::mutex mutex;
};

using PySegmenter = Guarded<Segmenter>;
using PySubtractor = Guarded<cv::Ptr<cv::BackgroundSubtractor>>;

Result process(PySegmenter& segmenter, const py::array& frame) {
  const cv::Mat mat = matFromArray(frame);
  return segmenter.run([&](Segmenter& s) { return s.process(mat); });
}

// cv2's BackgroundSubtractor.apply(image[, fgmask[, learningRate]]) -> fgmask.
py::object apply(PySubtractor& subtractor, const py::array& image, const py::object& fgmask,
                 double learning_rate) {
  const cv::Mat frame = matFromArray(image);
  const cv::Mat mask = subtractor.run([&](cv::Ptr<cv::BackgroundSubtractor>& s) {
    cv::Mat out;
    s->apply(frame, out, learning_rate);
    return out;
  });
  if (fgmask.is_none()) return arrayFromMat(mask);
  if (!py::isinstance<py::array>(fgmask) || !fgmask.cast<py::array>().writeable()) {
    throw std::invalid_argument("fgmask must be a writeable numpy array");
  }
  const auto out = fgmask.cast<py::array>();
  if (out.ndim() != 2 || !py::isinstance<py::array_t<std::uint8_t>>(out) ||
      out.shape(0) != mask.rows || out.shape(1) != mask.cols) {
    throw std::invalid_argument("fgmask must be an HxW uint8 array of the frame's size");
  }
  // numpy writes in place whatever the array's strides (a view, Fortran order).
  out.attr("__setitem__")(py::ellipsis(), arrayFromMat(mask));
  return fgmask;
}

py::object backgroundImage(PySubtractor& subtractor) {
  return arrayFromMat(subtractor.run([](cv::Ptr<cv::BackgroundSubtractor>& s) {
    cv::Mat background;
    s->getBackgroundImage(background);
    return background;
  }));
}

}  // namespace

void bindSegmenter(py::module_& module) {
  py::class_<PySegmenter>(module, "Segmenter",
                          "Segments the moving objects of a video, one frame at a time; each "
                          "frame is compared with the previous one only. Use one Segmenter per "
                          "stream.")
      .def(py::init([](const Params& p) { return std::make_unique<PySegmenter>(Segmenter(p)); }),
           py::arg("params") = Params(), "Raises ValueError when the parameters are out of range.")
      .def("process", &process, py::arg("frame"),
           "Takes the next frame (HxWx3 BGR as cv2 reads it, HxW grey or HxWx4 BGRA; uint8 or "
           "uint16) and returns its Result. The first frame's mask is empty. Raises ValueError "
           "for an empty frame or an unsupported shape or dtype.")
      .def("reset", [](PySegmenter& s) { s.run([](Segmenter& segmenter) { segmenter.reset(); }); },
           "Forgets the previous frame.")
      .def("compensated_previous_frame",
           [](PySegmenter& s) {
             return arrayFromMat(s.run([](Segmenter& segmenter) {
               return segmenter.compensatedPreviousFrame();
             }));
           },
           "The previous frame warped onto the last one (HxWx3 uint8 BGR); None before the "
           "second frame.")
      .def_property_readonly(
          "params",
          [](PySegmenter& s) {
            return s.run([](Segmenter& segmenter) { return segmenter.params(); });
          },
          "A copy of the parameters.");

  py::class_<PySubtractor>(
      module, "BackgroundSubtractor",
      "cv2.BackgroundSubtractor's interface over a Segmenter (see createMovingCameraSubtractor).")
      .def("apply", &apply, py::arg("image"), py::arg("fgmask") = py::none(),
           py::arg("learningRate") = -1.0,
           "Segments the next frame and returns its HxW uint8 mask (0 / 255), written into "
           "fgmask when one is given. learningRate is ignored: there is no background model.")
      .def("getBackgroundImage", &backgroundImage,
           "The previous frame warped onto the last one; None before the second frame.");
  module.def(
      "createMovingCameraSubtractor",
      [](const Params& params) {
        return std::make_unique<PySubtractor>(createMovingCameraSubtractor(params));
      },
      py::arg("params") = Params(),
      "Drop-in for cv2.createBackgroundSubtractorMOG2() when the camera moves.");
}

}  // namespace movseg::python
