// A scene cut (or a camera jump beyond Lucas-Kanade's reach) seen in the compensated difference
// of eq. (4). Across a cut RANSAC still fits a camera model to chance matches; that model either
// maps the previous frame mostly off the current one, or leaves most of the picture different
// after alignment — where between two frames of one scene only what moves differs.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// Measured on DAVIS 2016 (docs/reliability.md): consecutive frames kept at least 71 % of the
// picture covered and a median d of at most 772 over it; cuts between its sequences fell below
// the coverage or had a median of 605 to 10,000 and more.
constexpr double kSceneCutCoverage = 0.5;
constexpr double kSceneCutMedianDifference = 1000;  // (8-bit levels)^2: an RMS of 32 levels

// Whether the pair is unrelated, from its compensated difference `difference` (CV_32F, eq. 4)
// and the camera `model` that made it (previous to current frame, at the difference's scale):
// the warped previous frame covers less than kSceneCutCoverage of the current one, or the
// median of d over what it covers exceeds kSceneCutMedianDifference.
bool isSceneCut(const cv::Mat& difference, const cv::Matx33d& model);

// The rule alone, from a pair's pixel counts: of `total` pixels of the current frame the warped
// previous frame covers `covered`, and of those `differing` have d above
// kSceneCutMedianDifference. More than half of them differing is a median above it: counted,
// not sorted (a partial sort of a frame's values cost more than the rest of the check).
bool isSceneCut(long total, long covered, long differing);

}  // namespace movseg
