// §3.1 over a stream: each frame is prepared once and aligned with the previous one, the model
// of each pair warm-starting the next. Shared by the paper's Segmenter and the baselines that
// need the camera motion (diff, mog2-comp).
#pragma once

#include <cstdint>
#include <optional>

#include <opencv2/core.hpp>

#include "core/frame.h"
#include "motion/compensation.h"
#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

// Where the pair's static scene is seen in the current frame, in pixels of a frame scaled by
// `scale` from full resolution: the background matches S_b, or (static camera, failed
// alignment) the current frame's features, most of which lie on the background.
std::vector<cv::Point2f> staticPoints(const MotionEstimate& motion, const PreparedFrame& current,
                                      double scale);

class CameraTracker {
 public:
  explicit CameraTracker(const Params& params);

  struct Step {
    const PreparedFrame* previous = nullptr;  // null for a first frame
    const PreparedFrame* current = nullptr;
    MotionEstimate motion;                    // alignment scale (empty on a first frame)
  };

  // Takes the next frame (any type toBgr8() accepts; throws std::invalid_argument as it does).
  // Fills the motion part of *diag (model in full-resolution pixels, counts, flags,
  // prepare/motion timings). A frame of another size restarts the stream (diag->reset). The
  // returned pointers stay valid until the next call.
  Step advance(const cv::Mat& frame, Diagnostics* diag);

  void reset();

 private:
  Params params_;
  std::optional<PreparedFrame> previous_, current_;
  cv::Matx33d warm_model_ = cv::Matx33d::eye();  // alignment scale
  std::uint64_t pairs_ = 0;
};

}  // namespace movseg
