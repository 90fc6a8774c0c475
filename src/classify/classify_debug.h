// Debug picture of §3.2 (the paper's Fig. 3 and Fig. 4(c)).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/segmenter.h"

namespace movseg {

// Feature points on the frame: foreground red, background blue, unknown yellow.
cv::Mat drawFeatures(const cv::Mat& bgr, const std::vector<cv::Point2f>& points,
                     const std::vector<FeatureLabel>& labels);

}  // namespace movseg
