// Debug picture of the edge snap: where it moved the cut's outline.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// The frame's brightness (8-bit, the snap's guide) darkened, the cut's mask (`cut`, CV_8U
// 0/255) grey over it, the pixels the snap added to it green and those it took away red
// (`snapped`: EdgeSnap's output, above 127 moving; all three of one size).
cv::Mat drawEdgeSnap(const cv::Mat& grey, const cv::Mat& cut, const cv::Mat& snapped);

}  // namespace movseg
