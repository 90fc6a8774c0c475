// Images of uniform random levels for the tests that compare movseg's remaps and box means
// with OpenCV's.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// CV_8U, each pixel drawn from [low, high).
inline cv::Mat randomImage(cv::Size size, uint64 seed, int low = 0, int high = 256) {
  cv::Mat image(size, CV_8U);
  cv::RNG(seed).fill(image, cv::RNG::UNIFORM, low, high);
  return image;
}

}  // namespace movseg
