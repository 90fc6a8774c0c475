// Dense optical flow over a stream (DIS, Kroeger et al. 2016, OpenCV's cv::DISOpticalFlow):
// from each frame to the previous one, so that the motion is known at the current frame's
// pixels, each pair starting from the previous pair's flow.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/video/tracking.hpp>

namespace movseg {

class DenseFlow {
 public:
  // `finest_scale`: the pyramid level DIS stops at (0 = full resolution, 1 = half, ...).
  explicit DenseFlow(int finest_scale);

  // Writes the flow of `grey` (8-bit, continuous) to the previous frame given into *flow:
  // current(p) matches previous(p + flow(p)); CV_32FC2 of grey's size, or empty for a first
  // frame (or one of another size, or one under 16 pixels a side). `grey` and *flow are read again by the next call (the next
  // frame is matched against `grey`, starting from *flow), so the caller keeps them unchanged
  // until then; the buffers are the caller's, so that two frames can be in flight.
  void next(const cv::Mat& grey, cv::Mat* flow);

  void reset();

 private:
  cv::Ptr<cv::DISOpticalFlow> dis_;
  cv::Mat previous_grey_, previous_flow_;  // the last call's, shared with its caller
};

}  // namespace movseg
