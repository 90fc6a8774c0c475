#include "pipelines/tracked.h"

#include <algorithm>

#include "classify/scene_cut.h"
#include "motion/compensation.h"
#include "motion/model.h"
#include "motion/motion_debug.h"

namespace movseg {

void analyseTracked(CameraTracker* tracker, const cv::Mat& bgr, Analysis* analysis) {
  static_cast<TrackedAnalysis*>(analysis)->step = tracker->advance(bgr);
}

void describeMotion(const CameraTracker::Step& step, Diagnostics* diag) {
  const MotionEstimate& motion = step.motion;
  diag->model = step.model;
  diag->model_is_affine = isAffine(step.model);
  diag->features = motion.features;
  diag->tracks = motion.tracks;
  diag->matches = static_cast<int>(motion.matches.size());
  diag->background_matches =
      static_cast<int>(std::count(motion.background.begin(), motion.background.end(), 1));
  diag->foreground_matches = diag->matches - diag->background_matches;
  diag->outer_iterations = motion.outer_iterations;
  diag->motion_fallback = motion.fallback;
  diag->prepare_ms = step.prepare_ms;
  diag->motion_ms = step.motion_ms;
}

cv::Mat compensatedDifferenceOf(const CameraTracker::Step& step, const DebugSink& debug,
                                Diagnostics* diag) {
  const PreparedFrame& current = step.current->image;
  const cv::Matx33d model = rescaleModel(step.model, current.seg_scale);
  const cv::Mat difference =
      compensatedDifference(step.previous->image.seg_smooth, current.seg_smooth, model);
  debug.put("difference", [&] { return drawDifference(difference); });
  diag->scene_cut = isSceneCut(difference, model);
  return difference;
}

}  // namespace movseg
