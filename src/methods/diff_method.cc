#include "classify/classify.h"
#include "methods/baselines.h"
#include "methods/method_support.h"
#include "motion/model.h"

namespace movseg {
namespace {

class DiffMethod : public TrackedMethod {
 public:
  using TrackedMethod::TrackedMethod;

 protected:
  cv::Mat maskFor(const CameraTracker::Step& step, Diagnostics* diag) override {
    const PreparedFrame& cur = *step.current;
    if (step.previous == nullptr) return cv::Mat::zeros(cur.seg_bgr.size(), CV_8U);
    const cv::Matx33d model = rescaleModel(diag->model, cur.seg_scale);
    const cv::Mat d = compensatedDifference(step.previous->seg_smooth, cur.seg_smooth, model);
    diag->lambda = chooseLambda(d, staticPoints(step.motion, cur, cur.seg_scale), params_);
    return d > diag->lambda;
  }
};

}  // namespace

std::unique_ptr<Method> makeDiffMethod(const Params& params) {
  params.check();
  return std::make_unique<DiffMethod>(params);
}

}  // namespace movseg
