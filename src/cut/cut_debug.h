// Debug picture of §3.3: the geodesic confidence u(x) of eq. (10).
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// u(x) as a heat map scaled to its own maximum (dark: uncertain, bright: decided).
cv::Mat drawConfidence(const cv::Mat& confidence);

}  // namespace movseg
