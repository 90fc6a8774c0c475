// Debug pictures of §3.1 (the paper's Fig. 2 and Fig. 4(b)).
#pragma once

#include <opencv2/core.hpp>

#include "motion/compensation.h"

namespace movseg {

// Matches S_m drawn on the current frame at the alignment scale: background (S_b) blue,
// foreground (S_f) red, each with a line from where it was in the previous frame.
cv::Mat drawMatches(const cv::Mat& grey, const MotionEstimate& motion);

// The compensated difference d (eq. 4) as a heat map: black is 0, white is 1024 and above.
cv::Mat drawDifference(const cv::Mat& difference);

}  // namespace movseg
