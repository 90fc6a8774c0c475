// PNG frames read with libpng directly, as cv::imread reads them but without a word on stderr:
// libpng prints its error ("Not enough image data", a bad CRC) before OpenCV sees the failure,
// and the CLI's errors are one line. Only the formats frames come in are decoded here (8-bit
// grey or RGB without transparency, read unchanged); any other is left to cv::imdecode.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Whether `bytes` start with the PNG signature.
bool isPng(const std::vector<uchar>& bytes);

struct PngRead {
  bool damaged = false;  // libpng gave up on it
  cv::Mat image;         // decoded: BGR or grey; empty when damaged or not a format decoded here
};

// Reads the PNG file `bytes` (isPng()).
PngRead readPng(const std::vector<uchar>& bytes);

}  // namespace movseg
