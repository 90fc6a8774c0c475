// numpy arrays <-> cv::Mat without copying pixels.
#pragma once

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>

namespace movseg::python {

// A cv::Mat over the array's memory (HxW or HxWxC; uint8, int8, uint16, int16, float32 or
// float64). The Mat holds a reference to the array, so copies the Segmenter keeps stay valid
// after the call. Arrays whose pixels or channels are not packed are copied once first. An empty
// array gives an empty Mat. Throws std::invalid_argument for other shapes and types.
cv::Mat matFromArray(const pybind11::array& array);

// A frame for Segmenter::process: matFromArray(), with the channels of an RGB or RGBA array put
// in BGR order when `rgb` is set (a copy). Throws pybind11::type_error naming the type of
// anything but a numpy array, without printing its value (a list of frames can be long).
cv::Mat frameFromArray(const pybind11::object& frame, bool rgb);

// A numpy array over the Mat's memory (HxW for one channel, else HxWxC), which keeps the Mat's
// buffer alive; None for an empty Mat.
pybind11::object arrayFromMat(const cv::Mat& mat);

}  // namespace movseg::python
