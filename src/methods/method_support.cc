#include "methods/method_support.h"

namespace movseg {

Result TrackedMethod::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  Result result;
  const CameraTracker::Step step = tracker_.advance(frame, &result.diagnostics);
  result.mask = upscaledMask(maskFor(step, &result.diagnostics), step.current->bgr.size());
  result.diagnostics.timings.total_ms = millisecondsSince(start);
  return result;
}

}  // namespace movseg
