// What the pipelines built on the CameraTracker (§3.1) share: their analysis is the tracker's
// step, and they report it the same way.
#pragma once

#include "motion/camera_tracker.h"
#include "movseg/segmenter.h"
#include "pipelines/pipeline.h"

namespace movseg {

struct TrackedAnalysis : Analysis {
  CameraTracker::Step step;
};

// Phase 1 of a tracked pipeline: the tracker's next step.
void analyseTracked(CameraTracker* tracker, const cv::Mat& bgr, Analysis* analysis);

// The camera model (full resolution), the feature, track and match counts, the fallback flag
// and the prepare / motion times of `step`.
void describeMotion(const CameraTracker::Step& step, Diagnostics* diag);

// Eq. (4) at the segmentation scale: the step's previous frame warped onto its current one by
// the camera, their difference d (debug picture `difference`), and whether the pair is a scene
// cut (diag->scene_cut). `step` has a previous frame.
cv::Mat compensatedDifferenceOf(const CameraTracker::Step& step, const DebugSink& debug,
                                Diagnostics* diag);

}  // namespace movseg
