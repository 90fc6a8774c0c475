// The parts of the Python module movseg, each registered by one function.
#pragma once

#include <pybind11/pybind11.h>

namespace movseg::python {

void bindParams(pybind11::module_& module);     // Params
void bindResult(pybind11::module_& module);     // Result, Diagnostics
void bindSegmenter(pybind11::module_& module);  // Segmenter, StreamSegmenter,
                                                // createMovingCameraSubtractor

}  // namespace movseg::python
