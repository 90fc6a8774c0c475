#include "motion/camera_tracker.h"

#include "core/timing.h"
#include "motion/model.h"

namespace movseg {

std::vector<cv::Point2f> CameraTracker::Step::staticPoints(double scale) const {
  const auto s = static_cast<float>(scale / current->image.align_scale);
  std::vector<cv::Point2f> points;
  for (size_t i = 0; i < motion.matches.size(); ++i) {
    if (motion.background[i]) points.push_back(motion.matches[i].cur * s);
  }
  if (points.empty() || motion.fallback) {
    points.clear();
    for (const cv::Point2f& p : current->alignment.features) points.push_back(p * s);
  }
  return points;
}

CameraTracker::CameraTracker(const Params& params) : params_(params) {}

CameraTracker::Step CameraTracker::advance(const cv::Mat& bgr) {
  const Clock::time_point start = Clock::now();
  auto frame = std::make_shared<TrackedFrame>();
  frame->image = prepareFrame(bgr, params_);
  frame->alignment = prepareAlignment(frame->image.small_grey, params_);
  previous_ = std::move(current_);
  current_ = frame;
  const TrackedFrame& current = *frame;
  Step step;
  step.current = current_;
  step.prepare_ms = millisecondsSince(start);
  if (!previous_) {
    warm_model_ = cv::Matx33d::eye();
    return step;
  }
  step.previous = previous_;
  const Clock::time_point motion_start = Clock::now();
  if (!params_.static_camera) {
    step.motion = estimateCameraMotion(previous_->alignment, current.alignment, warm_model_,
                                       params_, params_.seed + pairs_);
    if (!step.motion.fallback) warm_model_ = step.motion.model;
  }
  ++pairs_;
  step.model = last_model_ = rescaleModel(step.motion.model, 1.0 / current.image.align_scale);
  step.motion_ms = millisecondsSince(motion_start);
  return step;
}

void CameraTracker::reset() {
  previous_.reset();
  current_.reset();
  warm_model_ = cv::Matx33d::eye();
}

cv::Mat CameraTracker::compensatedPreviousFrame() const {
  if (!previous_ || !current_) return cv::Mat();
  return warpPrevious(previous_->image.bgr, current_->image.bgr, last_model_);
}

}  // namespace movseg
