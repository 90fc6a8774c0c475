// `diff`: the compensated frame difference of §3.1 thresholded by eq. (3) — the paper's pipeline
// cut off before §3.2 (no GMM refinement, no geodesic cut). A baseline.
#include "classify/classify.h"
#include "core/timing.h"
#include "motion/camera_tracker.h"
#include "pipelines/pipeline.h"
#include "pipelines/tracked.h"

namespace movseg {
namespace {

class DiffPipeline : public Pipeline {
 public:
  explicit DiffPipeline(const Params& params) : params_(params), tracker_(params) {}

  std::unique_ptr<Analysis> newAnalysis() const override {
    return std::make_unique<TrackedAnalysis>();
  }

  void analyse(const cv::Mat& bgr, Analysis* analysis) override {
    analyseTracked(&tracker_, bgr, analysis);
  }

  cv::Mat segment(const Analysis& analysis, const DebugSink& debug, Result* result) override {
    const CameraTracker::Step& step = static_cast<const TrackedAnalysis&>(analysis).step;
    Diagnostics& diag = result->diagnostics;
    describeMotion(step, &diag);
    const PreparedFrame& cur = step.current->image;
    if (step.previous == nullptr) return cv::Mat::zeros(cur.seg_bgr.size(), CV_8U);
    const Clock::time_point start = Clock::now();
    const cv::Mat d = compensatedDifferenceOf(step, debug, &diag);
    diag.lambda = chooseLambda(d, step.staticPoints(cur.seg_scale), params_);
    diag.classify_ms = millisecondsSince(start);
    return d > diag.lambda;
  }

  void reset() override { tracker_.reset(); }

  cv::Mat compensatedPreviousFrame() const override { return tracker_.compensatedPreviousFrame(); }

 private:
  Params params_;
  CameraTracker tracker_;
};

}  // namespace

std::unique_ptr<Pipeline> makeDiffPipeline(const Params& params) {
  return std::make_unique<DiffPipeline>(params);
}

}  // namespace movseg
