#include "classify/classify.h"
#include "core/camera_tracker.h"
#include "methods/baselines.h"
#include "methods/method_support.h"
#include "motion/model.h"

namespace movseg {
namespace {

class DiffMethod : public Method {
 public:
  explicit DiffMethod(const Params& params) : params_(params), tracker_(params) {}

  Result process(const cv::Mat& frame) override {
    const Clock::time_point start = Clock::now();
    Result result;
    Diagnostics& diag = result.diagnostics;
    const CameraTracker::Step step = tracker_.advance(toBgr8(frame), &diag);
    const PreparedFrame& cur = *step.current;
    if (step.previous == nullptr) {
      result.mask = cv::Mat::zeros(cur.bgr.size(), CV_8U);
    } else {
      const cv::Matx33d model = rescaleModel(diag.model, cur.seg_scale);
      const cv::Mat d = compensatedDifference(step.previous->seg_smooth, cur.seg_smooth, model);
      diag.lambda = chooseLambda(d, staticPoints(step.motion, cur, cur.seg_scale), params_);
      result.mask = upscaledMask(d > diag.lambda, cur.bgr.size());
    }
    diag.timings.total_ms = millisecondsSince(start);
    return result;
  }

 private:
  Params params_;
  CameraTracker tracker_;
};

}  // namespace

std::unique_ptr<Method> makeDiffMethod(const Params& params) {
  params.check();
  return std::make_unique<DiffMethod>(params);
}

}  // namespace movseg
