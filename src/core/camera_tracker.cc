#include "core/camera_tracker.h"

#include <algorithm>

#include "core/timing.h"
#include "motion/model.h"

namespace movseg {
namespace {

void describeMotion(const MotionEstimate& motion, double align_scale, Diagnostics* diag) {
  diag->model = rescaleModel(motion.model, 1.0 / align_scale);
  diag->model_is_affine = isAffine(diag->model);
  diag->features = motion.features;
  diag->tracks = motion.tracks;
  diag->matches = static_cast<int>(motion.matches.size());
  diag->background_matches =
      static_cast<int>(std::count(motion.background.begin(), motion.background.end(), 1));
  diag->foreground_matches = diag->matches - diag->background_matches;
  diag->outer_iterations = motion.outer_iterations;
}

}  // namespace

std::vector<cv::Point2f> staticPoints(const MotionEstimate& motion, const PreparedFrame& current,
                                      double scale) {
  const auto s = static_cast<float>(scale / current.align_scale);
  std::vector<cv::Point2f> points;
  for (size_t i = 0; i < motion.matches.size(); ++i) {
    if (motion.background[i]) points.push_back(motion.matches[i].cur * s);
  }
  if (points.empty() || motion.fallback) {
    points.clear();
    for (const cv::Point2f& p : current.features) points.push_back(p * s);
  }
  return points;
}

CameraTracker::CameraTracker(const Params& params) : params_(params) {}

CameraTracker::Step CameraTracker::advance(const cv::Mat& frame, Diagnostics* diag) {
  const Clock::time_point start = Clock::now();
  // The frame is kept as the next pair's previous one, so it must not share the caller's
  // buffer: a video loop (cap >> frame) refills that buffer with the next frame.
  cv::Mat bgr = toBgr8(frame);
  if (bgr.data == frame.data) bgr = bgr.clone();
  if (current_) previous_ = std::move(current_);
  if (previous_ && previous_->bgr.size() != bgr.size()) {
    reset();
    diag->reset = true;
  }
  current_ = prepareFrame(bgr, params_);
  diag->timings.prepare_ms = millisecondsSince(start);
  Step step;
  step.current = &*current_;
  if (!previous_) {
    diag->first_frame = true;
    warm_model_ = cv::Matx33d::eye();
    return step;
  }
  step.previous = &*previous_;
  const Clock::time_point motion_start = Clock::now();
  if (!params_.static_camera) {
    step.motion =
        estimateCameraMotion(*previous_, *current_, warm_model_, params_, params_.seed + pairs_);
    if (!step.motion.fallback) warm_model_ = step.motion.model;
    diag->motion_fallback = step.motion.fallback;
  }
  ++pairs_;
  describeMotion(step.motion, current_->align_scale, diag);
  diag->timings.motion_ms = millisecondsSince(motion_start);
  return step;
}

void CameraTracker::reset() {
  previous_.reset();
  current_.reset();
  warm_model_ = cv::Matx33d::eye();
}

}  // namespace movseg
