// A scene cut (or a camera jump beyond Lucas-Kanade's reach) seen in the compensated difference
// of eq. (4): no camera model relates the two frames, so most of the picture differs after
// alignment, where between two frames of one scene only what moves does.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// The median of d (CV_32F, (8-bit levels)^2) above which a pair is taken for unrelated frames.
// Measured on DAVIS 2016 (docs/reliability.md): consecutive frames stay far below it, cuts
// between its sequences far above.
constexpr double kSceneCutMedianDifference = 400;

// Whether the pair whose compensated difference is `difference` is unrelated: its median d
// exceeds kSceneCutMedianDifference.
bool isSceneCut(const cv::Mat& difference);

}  // namespace movseg
