// The diagnostics of §3.1, shared by the pipelines built on the CameraTracker.
#pragma once

#include "motion/camera_tracker.h"
#include "movseg/segmenter.h"

namespace movseg {

// The camera model (full resolution), the feature, track and match counts, the fallback flag
// and the prepare / motion times of `step`.
void describeMotion(const CameraTracker::Step& step, Diagnostics* diag);

}  // namespace movseg
