// The picture a person looks at: the mask tinted over the frame, the feature points as dots,
// and a small heads-up display.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "movseg/segmenter.h"

namespace movseg {

// `frame` is the input as given (converted to 8-bit BGR here); `hud` is drawn top-left; the
// features are drawn when `feature_dots` is set.
cv::Mat drawOverlay(const cv::Mat& frame, const Result& result, const std::string& hud,
                    bool feature_dots = true);

}  // namespace movseg
