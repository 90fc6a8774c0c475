#include "ndarray.h"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace movseg::python {
namespace {

// Lets Mats share a numpy array's memory the way OpenCV's own cv2 module does: the Mat's
// UMatData owns a reference to the array, released when the last Mat sharing it goes away.
// Buffers OpenCV allocates for such a Mat (create() with another size) come from the default
// allocator.
class NumpyAllocator : public cv::MatAllocator {
 public:
  cv::UMatData* wrap(py::array array) const {
    auto* u = new cv::UMatData(this);
    u->data = u->origdata = static_cast<uchar*>(const_cast<void*>(array.data()));
    u->size = static_cast<size_t>(array.shape(0) * array.strides(0));
    u->userdata = array.release().ptr();
    return u;
  }

  cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step,
                         cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
    return cv::Mat::getDefaultAllocator()->allocate(dims, sizes, type, data, step, flags, usage);
  }
  bool allocate(cv::UMatData* u, cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
    return cv::Mat::getDefaultAllocator()->allocate(u, flags, usage);
  }
  // May run with the GIL released (inside Segmenter::process), hence the acquire.
  void deallocate(cv::UMatData* u) const override {
    if (u == nullptr) return;
    py::gil_scoped_acquire gil;
    Py_XDECREF(static_cast<PyObject*>(u->userdata));
    delete u;
  }
};

// cv::Mat stores a non-const allocator pointer.
NumpyAllocator& numpyAllocator() {
  static NumpyAllocator* allocator = new NumpyAllocator;  // Mats may outlive any static
  return *allocator;
}

int depthOf(const py::array& array) {
  if (py::isinstance<py::array_t<std::uint8_t>>(array)) return CV_8U;
  if (py::isinstance<py::array_t<std::int8_t>>(array)) return CV_8S;
  if (py::isinstance<py::array_t<std::uint16_t>>(array)) return CV_16U;
  if (py::isinstance<py::array_t<std::int16_t>>(array)) return CV_16S;
  if (py::isinstance<py::array_t<float>>(array)) return CV_32F;
  if (py::isinstance<py::array_t<double>>(array)) return CV_64F;
  const std::string dtype = py::str(array.dtype());
  throw std::invalid_argument("unsupported frame dtype " + dtype +
                              " (expected uint8, uint16, int8, int16, float32 or float64)");
}

// cv::Mat rows may be padded, but the pixels of a row and the channels of a pixel must be packed.
bool packedRows(const py::array& array, py::ssize_t channels) {
  const py::ssize_t item = array.itemsize();
  if (array.ndim() == 3 && array.strides(2) != item) return false;
  return array.strides(1) == item * channels && array.strides(0) % item == 0 &&
         array.strides(0) >= array.strides(1) * array.shape(1);
}

py::dtype dtypeOf(int depth) {
  switch (depth) {
    case CV_8U: return py::dtype::of<std::uint8_t>();
    case CV_8S: return py::dtype::of<std::int8_t>();
    case CV_16U: return py::dtype::of<std::uint16_t>();
    case CV_16S: return py::dtype::of<std::int16_t>();
    case CV_32S: return py::dtype::of<std::int32_t>();
    case CV_32F: return py::dtype::of<float>();
    case CV_64F: return py::dtype::of<double>();
    default:
      throw std::invalid_argument("no numpy dtype for OpenCV depth " + std::to_string(depth));
  }
}

}  // namespace

cv::Mat matFromArray(const py::array& input) {
  if (input.ndim() != 2 && input.ndim() != 3) {
    throw std::invalid_argument("expected a frame of shape HxW or HxWxC, got " +
                                std::to_string(input.ndim()) + " dimensions");
  }
  const int depth = depthOf(input);
  if (input.size() == 0) return cv::Mat();
  for (int axis = 0; axis < 2; ++axis) {
    if (input.shape(axis) > std::numeric_limits<int>::max()) {
      throw std::invalid_argument("frame dimension " + std::to_string(input.shape(axis)) +
                                  " does not fit in an int");
    }
  }
  const py::ssize_t channels = input.ndim() == 3 ? input.shape(2) : 1;
  if (channels > CV_CN_MAX) {
    throw std::invalid_argument("unsupported channel count " + std::to_string(channels) +
                                " (expected 1, 3 or 4)");
  }
  const py::array array =
      packedRows(input, channels) ? input : py::array::ensure(input, py::array::c_style);
  cv::Mat mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
              CV_MAKETYPE(depth, static_cast<int>(channels)), const_cast<void*>(array.data()),
              static_cast<size_t>(array.strides(0)));
  mat.u = numpyAllocator().wrap(array);
  mat.addref();
  mat.allocator = &numpyAllocator();
  return mat;
}

cv::Mat frameFromArray(const py::object& frame, bool rgb) {
  if (!py::isinstance<py::array>(frame)) {
    throw py::type_error("expected the frame as a numpy array (HxW, HxWx3 or HxWx4), got " +
                         py::str(py::type::of(frame).attr("__name__")).cast<std::string>());
  }
  const cv::Mat mat = matFromArray(frame.cast<py::array>());
  if (!rgb || (mat.channels() != 3 && mat.channels() != 4)) return mat;
  // Channels 0 and 2 swap places; alpha stays. mixChannels takes every depth.
  cv::Mat bgr(mat.size(), mat.type());
  const int from_to[] = {0, 2, 1, 1, 2, 0, 3, 3};
  cv::mixChannels(&mat, 1, &bgr, 1, from_to, static_cast<size_t>(mat.channels()));
  return bgr;
}

py::object arrayFromMat(const cv::Mat& mat) {
  if (mat.empty()) return py::none();
  auto* owner = new cv::Mat(mat);
  const py::capsule base(owner, [](void* p) { delete static_cast<cv::Mat*>(p); });
  std::vector<py::ssize_t> shape{mat.rows, mat.cols};
  std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(mat.step[0]),
                                   static_cast<py::ssize_t>(mat.elemSize())};
  if (mat.channels() > 1) {
    shape.push_back(mat.channels());
    strides.push_back(static_cast<py::ssize_t>(mat.elemSize1()));
  }
  return py::array(dtypeOf(mat.depth()), shape, strides, mat.data, base);
}

}  // namespace movseg::python
