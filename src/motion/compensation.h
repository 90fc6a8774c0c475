// §3.1 camera motion compensation: Algorithm 1's two-layer iteration over the tracked
// features, and the compensated frame difference of eq. (4).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "motion/features.h"
#include "motion/tracking.h"
#include "movseg/params.h"

namespace movseg {

struct MotionEstimate {
  cv::Matx33d model = cv::Matx33d::eye();  // previous -> current, alignment-scale pixels
  std::vector<Track> matches;              // S_m, alignment scale
  std::vector<char> background;            // per match: in S_b (1) or S_f (0)
  int features = 0;                        // detected in the previous frame
  int tracks = 0;                          // tracked forward and backward by LK
  int outer_iterations = 0;
  bool fallback = false;                   // too few matches: `warm` returned unchanged
};

// Algorithm 1. `warm` is the previous pair's model (alignment scale): it predicts the LK
// positions and is RANSAC's first hypothesis when params.warm_start is set, and it is the
// fallback when the pair cannot be aligned (textureless frame, scene cut).
MotionEstimate estimateCameraMotion(const AlignmentFrame& prev, const AlignmentFrame& cur,
                                    const cv::Matx33d& warm, const Params& params,
                                    std::uint64_t seed);

// I'(t) of eq. (4): `prev` warped by `model` (previous -> current, in these images' pixels)
// onto `cur`'s grid; where `prev` has no pixel, `cur`'s own value stands in.
cv::Mat warpPrevious(const cv::Mat& prev, const cv::Mat& cur, const cv::Matx33d& model);

// Eq. (4) for every pixel: the mean over colour channels of the squared difference between
// `cur` and warpPrevious(prev, cur, model), so pixels `prev` does not cover score 0.
// Returns CV_32F of cur's size.
cv::Mat compensatedDifference(const cv::Mat& prev, const cv::Mat& cur, const cv::Matx33d& model);

}  // namespace movseg
