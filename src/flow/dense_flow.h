// Dense optical flow over a stream (DIS, Kroeger et al. 2016, as OpenCV's cv::DISOpticalFlow
// computes it: flow/dis_flow.h): from each frame to the previous one, so that the motion is known
// at the current frame's pixels, each pair starting from the previous pair's flow.
#pragma once

#include <opencv2/core.hpp>

#include "flow/dis_flow.h"

namespace movseg {

class DenseFlow {
 public:
  // `finest_scale`: the pyramid level DIS stops at (0 = full resolution, 1 = half, ...).
  explicit DenseFlow(int finest_scale);

  // Writes the flow of `grey` (8-bit, continuous) to the previous frame given into *flow:
  // current(p) matches previous(p + flow(p)); CV_32FC2 of grey's size, or empty for a first
  // frame (or one of another size, or one under 16 pixels a side). *flow is read again by the
  // next call (the next pair starts from it), so the caller keeps it unchanged until then; the
  // buffers are the caller's, so that two frames can be in flight. `grey` is not kept: what the
  // next pair needs of it is prepared here once.
  void next(const cv::Mat& grey, cv::Mat* flow);

  void reset();

  // DisFlow::reach().
  int reach() const { return dis_.reach(); }

 private:
  DisFlow dis_;
  DisFrame frames_[2];    // the current and the previous frame, prepared
  int previous_ = -1;     // which of frames_ holds the previous frame; -1: none
  cv::Mat previous_flow_;  // the last call's, shared with its caller
};

}  // namespace movseg
