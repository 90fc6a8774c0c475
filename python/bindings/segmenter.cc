// movseg.Segmenter, movseg.StreamSegmenter, and movseg.createMovingCameraSubtractor for code
// written for cv2's MOG2.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <utility>

#include <pybind11/stl.h>

#include "bindings.h"
#include "movseg/background_subtractor.h"
#include "movseg/segmenter.h"
#include "movseg/stream_segmenter.h"
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
  template <typename... Args>
  explicit Guarded(std::in_place_t, Args&&... args) : object(std::forward<Args>(args)...) {}
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
using PyStream = Guarded<StreamSegmenter>;

Result process(PySegmenter& segmenter, const py::object& frame, bool rgb) {
  const cv::Mat mat = frameFromArray(frame, rgb);
  return segmenter.run([&](Segmenter& s) { return s.process(mat); });
}

// push() copies the frame before it returns: the array may be freed or refilled after the call.
std::optional<Result> push(PyStream& stream, const py::object& frame, bool rgb) {
  const cv::Mat mat = frameFromArray(frame, rgb);
  return stream.run([&](StreamSegmenter& s) { return s.push(mat); });
}

// set_ignored_region's region: None (none), or a 2-D array whose non-zero elements are ignored.
// Read with the GIL held, before the call that sets it releases it.
cv::Mat regionFromArray(const py::object& region) {
  if (region.is_none()) return cv::Mat();
  using Bytes = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
  const Bytes ignored = Bytes::ensure(py::module_::import("numpy").attr("not_equal")(region, 0));
  if (!ignored || ignored.ndim() != 2) {
    throw py::value_error("the ignored region must be a 2-D array (HxW), non-zero where ignored");
  }
  return cv::Mat(static_cast<int>(ignored.shape(0)), static_cast<int>(ignored.shape(1)), CV_8U,
                 const_cast<std::uint8_t*>(ignored.data()))
      .clone();
}

constexpr const char* kIgnoredRegionDoc =
    "Pixels that never move, from the next frame on: what is fixed to the camera (a dash-cam's "
    "bonnet, a burnt-in timestamp or logo). region: a 2-D array (HxW), non-zero where ignored, "
    "of any size (scaled to each frame's); None: none. The mask is 0 there; the dense method "
    "also leaves it out of what it measures. Raises ValueError for another shape.";

// A cv2.BackgroundSubtractor object as OpenCV's Python module lays it out (CVPY_TYPE_DECLARE in
// its modules/python/src2/pycompat.hpp): the object header, then the class's C++ object.
struct Cv2Subtractor {
  PyObject_HEAD
  cv::Ptr<cv::BackgroundSubtractor> object;
};

// A cv2.BackgroundSubtractor running movseg's subtractor: cv2's own object, whose C++ object is
// ours, so isinstance(s, cv2.BackgroundSubtractor) holds and every method (apply,
// getBackgroundImage, clear, ...) is cv2's, with cv2's conversions and errors, calling ours, as
// for MOG2. A Python subclass of cv2's class cannot do this: cv2 frees its objects as objects
// the garbage collector does not track, and every instance of a Python subclass is tracked, so
// it crashes when freed (measured: OpenCV 4.6, Python 3.11).
py::object movingCameraSubtractor(const Params& params, const py::object& ignored_region) {
  const cv::Mat ignored = regionFromArray(ignored_region);
  py::object subtractor = py::module_::import("cv2").attr("BackgroundSubtractor")();
  PyTypeObject* type = Py_TYPE(subtractor.ptr());
  if (type->tp_basicsize != static_cast<Py_ssize_t>(sizeof(Cv2Subtractor))) {
    throw std::runtime_error("this cv2 lays out cv2.BackgroundSubtractor unlike OpenCV 4 does: "
                             "use movseg.Segmenter");
  }
  reinterpret_cast<Cv2Subtractor*>(subtractor.ptr())->object = createMovingCameraSubtractor(params, ignored);
  return subtractor;
}

}  // namespace

void bindSegmenter(py::module_& module) {
  py::class_<PySegmenter>(module, "Segmenter",
                          "Segments the moving objects of a video, one frame at a time; each "
                          "frame's mask depends on it and the frames before it only. Use one "
                          "Segmenter per stream.")
      .def(py::init([](const Params& p) { return std::make_unique<PySegmenter>(std::in_place, p); }),
           py::arg("params") = Params(), "Raises ValueError when the parameters are out of range.")
      .def("process", &process, py::arg("frame"), py::kw_only(), py::arg("rgb") = false,
           "Takes the next frame, a numpy array: HxWx3 BGR as cv2 reads it, HxW grey or HxWx4 "
           "BGRA; with rgb=True, HxWx3 RGB or HxWx4 RGBA as PIL and imageio give them. uint8, "
           "uint16, int8, int16, or float32 / float64 with values in [0, 1] (a float frame in "
           "0-255 raises ValueError: pass uint8 or divide by 255). Returns its Result; the first "
           "frame's mask is empty. Raises ValueError for an empty frame or an unsupported shape, "
           "dtype or value range, TypeError for anything but a numpy array.")
      .def("reset", [](PySegmenter& s) { s.run([](Segmenter& segmenter) { segmenter.reset(); }); },
           "Forgets the previous frame.")
      .def("set_ignored_region",
           [](PySegmenter& s, const py::object& region) {
             const cv::Mat ignored = regionFromArray(region);
             s.run([&](Segmenter& segmenter) { segmenter.setIgnoredRegion(ignored); });
           },
           py::arg("region"), kIgnoredRegionDoc)
      .def("compensated_previous_frame",
           [](PySegmenter& s) {
             return arrayFromMat(s.run([](Segmenter& segmenter) {
               return segmenter.compensatedPreviousFrame();
             }));
           },
           "The previous frame warped onto the last one (HxWx3 uint8 BGR); None before the "
           "second frame, and always with method mog2, which fits no camera model.")
      .def_property_readonly(
          "params",
          [](PySegmenter& s) {
            return s.run([](Segmenter& segmenter) { return segmenter.params(); });
          },
          "A copy of the parameters.");

  py::class_<PyStream>(module, "StreamSegmenter",
                       "Segments one stream on two threads: while a frame is segmented, the next "
                       "is analysed. Masks identical to Segmenter's, one push later.")
      .def(py::init([](const Params& p, long long threads) {
             // Taken wide, so that a count beyond int is refused as any other one (ValueError),
             // not by pybind11's conversion (TypeError).
             const int count = threads == static_cast<int>(threads) ? static_cast<int>(threads) : 0;
             return std::make_unique<PyStream>(std::in_place, p, count);
           }),
           py::arg("params") = Params(), py::arg("threads") = 2,
           "threads: 2, or 1 (the same work in turn on the calling thread). Raises ValueError "
           "when the parameters are out of range or threads is not 1 or 2.")
      .def("push", &push, py::arg("frame"), py::kw_only(), py::arg("rgb") = false,
           "Takes the next frame (as Segmenter.process does) and returns the Result of the frame "
           "pushed before it; None on the stream's first push. Raises as Segmenter.process does.")
      .def("flush",
           [](PyStream& s) { return s.run([](StreamSegmenter& stream) { return stream.flush(); }); },
           "The Result of the last frame pushed, once; None when none is waiting.")
      .def("reset", [](PyStream& s) { s.run([](StreamSegmenter& stream) { stream.reset(); }); },
           "Forgets the stream, dropping a Result not yet returned (flush() first to keep it).")
      .def("set_ignored_region",
           [](PyStream& s, const py::object& region) {
             const cv::Mat ignored = regionFromArray(region);
             s.run([&](StreamSegmenter& stream) { stream.setIgnoredRegion(ignored); });
           },
           py::arg("region"), kIgnoredRegionDoc)
      .def_property_readonly(
          "params",
          [](PyStream& s) { return s.run([](StreamSegmenter& stream) { return stream.params(); }); },
          "A copy of the parameters.");

  module.def("createMovingCameraSubtractor", &movingCameraSubtractor, py::arg("params") = Params(),
             py::arg("ignored_region") = py::none(),
             "Drop-in for cv2.createBackgroundSubtractorMOG2() when the camera moves: a "
             "cv2.BackgroundSubtractor whose apply(image[, fgmask[, learningRate]]) segments the "
             "next frame (BGR, grey or BGRA, as cv2 reads them) and returns its mask, "
             "getBackgroundImage() gives the previous frame warped onto the last one and clear() "
             "forgets the stream. learningRate is ignored. ignored_region: what is fixed to the "
             "camera, as Segmenter.set_ignored_region takes it, for the subtractor's life. Use "
             "one per stream.");
}

}  // namespace movseg::python
