#include "methods/method_support.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Mat upscaledMask(const cv::Mat& mask, cv::Size size) {
  if (mask.size() == size) return mask;
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_LINEAR);
  cv::threshold(out, out, 127, 255, cv::THRESH_BINARY);
  return out;
}

Result TrackedMethod::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  Result result;
  const CameraTracker::Step step = tracker_.advance(frame, &result.diagnostics);
  result.mask = upscaledMask(maskFor(step, &result.diagnostics), step.current->bgr.size());
  result.diagnostics.timings.total_ms = millisecondsSince(start);
  return result;
}

}  // namespace movseg
