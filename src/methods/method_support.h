// Scaling a working-scale mask back to the frame's size, shared by every method.
#pragma once

#include <opencv2/core.hpp>

#include "core/timing.h"

namespace movseg {

// A 0/255 mask resized to `size` by bilinear interpolation and re-thresholded, so that a mask
// computed at a working scale has smooth rather than blocky boundaries at full resolution.
cv::Mat upscaledMask(const cv::Mat& mask, cv::Size size);

}  // namespace movseg
