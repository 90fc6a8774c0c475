// What the methods share: the frame loop of the methods that follow the camera.
#pragma once

#include <opencv2/core.hpp>

#include "core/camera_tracker.h"
#include "core/timing.h"
#include "methods/method.h"

namespace movseg {

// A method built on §3.1: process() converts the frame, advances the CameraTracker (filling the
// motion diagnostics), asks maskFor() for the mask, scales it to the frame and times the call.
class TrackedMethod : public Method {
 public:
  explicit TrackedMethod(const Params& params) : params_(params), tracker_(params) {}
  Result process(const cv::Mat& frame) final;

 protected:
  // The mask of the step's current frame, at any scale; may fill more of *diag.
  virtual cv::Mat maskFor(const CameraTracker::Step& step, Diagnostics* diag) = 0;

  const Params params_;

 private:
  CameraTracker tracker_;
};

}  // namespace movseg
