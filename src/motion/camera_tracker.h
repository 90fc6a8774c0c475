// §3.1 over a stream: each frame is prepared once and aligned with the previous one, the model
// of each pair warm-starting the next (§4.1). The stage every pipeline that follows the camera
// builds on.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "core/frame.h"
#include "motion/compensation.h"
#include "motion/features.h"
#include "movseg/params.h"

namespace movseg {

// A frame as the tracker keeps it: at its working scales, and as §3.1 sees it.
struct TrackedFrame {
  PreparedFrame image;
  AlignmentFrame alignment;
};

class CameraTracker {
 public:
  explicit CameraTracker(const Params& params);

  struct Step {
    // Shared with the tracker, so that a step outlives the tracker's next one (a stream
    // segments frame t while the tracker already aligns frame t+1).
    std::shared_ptr<const TrackedFrame> previous;  // null on a first frame
    std::shared_ptr<const TrackedFrame> current;
    MotionEstimate motion;                   // alignment scale; empty on a first frame
    cv::Matx33d model = cv::Matx33d::eye();  // motion.model in full-resolution pixels
    double prepare_ms = 0;                   // preparing the current frame
    double motion_ms = 0;                    // estimating the motion

    // Where the pair's static scene is seen in the current frame, in pixels of the frame
    // scaled by `scale` from full resolution: the background matches S_b, or (static camera,
    // failed alignment) the current frame's features, most of which lie on the background.
    std::vector<cv::Point2f> staticPoints(double scale) const;
  };

  // Takes the next frame (8-bit BGR; the tracker keeps it, so it must not be a buffer the
  // caller refills).
  Step advance(const cv::Mat& bgr);

  // Forgets every frame: the next one is a first frame.
  void reset();

  // The previous frame warped into the current one's coordinates; empty before a pair.
  cv::Mat compensatedPreviousFrame() const;

 private:
  Params params_;
  std::shared_ptr<const TrackedFrame> previous_, current_;
  cv::Matx33d warm_model_ = cv::Matx33d::eye();  // alignment scale
  cv::Matx33d last_model_ = cv::Matx33d::eye();  // full resolution
  std::uint64_t pairs_ = 0;
};

}  // namespace movseg
