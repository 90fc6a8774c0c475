// Debug pictures of the evidence stage (`dense`): what the pair says, what memory carries, and
// the log-odds the cut is given. Each is 8-bit, at the working scale.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// Residual motion (CV_32F, pixels): mid-grey where it is as large as the background's residual
// in this pair, `scale`; white from twice that.
cv::Mat drawResidual(const cv::Mat& residual, float scale);

// The photometric check's confirmation (CV_32F, [-1, 1]): white where the flow explains the patch
// better than the camera by the margin, black where the camera explains it better by the margin,
// mid-grey where neither does (flat patches, which any motion explains).
cv::Mat drawConfirmation(const cv::Mat& confirmation);

// The previous mask carried by the flow (CV_8U, or empty on a pair without one: black), of `size`.
cv::Mat drawCarried(const cv::Mat& carried, cv::Size size);

// Log-odds of motion (CV_32F): mid-grey undecided, 25 levels a unit, white moving.
cv::Mat drawLogOdds(const cv::Mat& log_odds);

}  // namespace movseg
