// Debug picture of §3.2 (the paper's Fig. 3 and Fig. 4(c)).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/segmenter.h"

namespace movseg {

// A feature's colour in every picture (BGR): foreground red, background blue, unknown yellow.
cv::Scalar labelColour(FeatureLabel label);

// Feature points on the frame, as dots of their label's colour.
cv::Mat drawFeatures(const cv::Mat& bgr, const std::vector<cv::Point2f>& points,
                     const std::vector<FeatureLabel>& labels);

}  // namespace movseg
