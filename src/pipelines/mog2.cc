// `mog2` and `mog2-comp`: OpenCV's MOG2 background subtractor, on the raw frames and in a frame
// stabilised by §3.1's camera model. Baselines: what a practitioner tries first.
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

#include "core/frame.h"
#include "motion/camera_tracker.h"
#include "motion/model.h"
#include "pipelines/pipeline.h"
#include "pipelines/tracked.h"

namespace movseg {
namespace {

// OpenCV's defaults (history 500, variance threshold 16) without shadow labels: the masks are
// binary like every other method's.
cv::Ptr<cv::BackgroundSubtractorMOG2> newMog2() {
  return cv::createBackgroundSubtractorMOG2(500, 16.0, false);
}

// Both MOG2 pipelines run at the segmentation scale, like the paper's cut, so the comparison is
// of methods rather than of resolutions.
class Mog2Pipeline : public Pipeline {
 public:
  explicit Mog2Pipeline(const Params& params) : params_(params) {}

  struct Frame : Analysis {
    cv::Mat resized;
  };

  std::unique_ptr<Analysis> newAnalysis() const override { return std::make_unique<Frame>(); }

  void analyse(const cv::Mat& bgr, Analysis* analysis) override {
    static_cast<Frame*>(analysis)->resized =
        resizedTo(bgr, workingSize(bgr.size(), params_.segmentation_width));
  }

  cv::Mat segment(const Analysis& analysis, const DebugSink&, Result*) override {
    if (analysis.first_frame) mog2_ = newMog2();  // a new stream: MOG2 cannot mix sizes
    cv::Mat mask;
    mog2_->apply(static_cast<const Frame&>(analysis).resized, mask);
    return mask;
  }

  void reset() override {}

  cv::Mat compensatedPreviousFrame() const override { return cv::Mat(); }

 private:
  Params params_;
  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2_ = newMog2();
};

// MOG2 in a stabilised reference frame. to_reference_ maps current segmentation-scale pixels
// to the reference's; when the current view covers less than half of the reference (the camera
// has panned away), the reference restarts at the current frame.
class CompensatedMog2Pipeline : public Pipeline {
 public:
  explicit CompensatedMog2Pipeline(const Params& params) : tracker_(params) {}

  std::unique_ptr<Analysis> newAnalysis() const override {
    return std::make_unique<TrackedAnalysis>();
  }

  void analyse(const cv::Mat& bgr, Analysis* analysis) override {
    analyseTracked(&tracker_, bgr, analysis);
  }

  cv::Mat segment(const Analysis& analysis, const DebugSink&, Result* result) override {
    const CameraTracker::Step& step = static_cast<const TrackedAnalysis&>(analysis).step;
    describeMotion(step, &result->diagnostics);
    const PreparedFrame& cur = step.current->image;
    const cv::Size size = cur.seg_bgr.size();
    if (step.previous == nullptr) {
      restart();
    } else {
      // previous -> current, so current -> reference is (previous -> reference) * inverse.
      to_reference_ = to_reference_ * rescaleModel(step.model, cur.seg_scale).inv();
      if (overlap(size) < 0.5) restart();
    }
    cv::Mat stabilised, mask_reference, mask;
    cv::warpPerspective(cur.seg_bgr, stabilised, cv::Mat(to_reference_), size);
    mog2_->apply(stabilised, mask_reference);
    cv::warpPerspective(mask_reference, mask, cv::Mat(to_reference_), size,
                        cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
    return mask;
  }

  void reset() override { tracker_.reset(); }

  cv::Mat compensatedPreviousFrame() const override { return tracker_.compensatedPreviousFrame(); }

 private:
  void restart() {
    mog2_ = newMog2();
    to_reference_ = cv::Matx33d::eye();
  }

  // The share of the reference frame that the current view's bounding box covers.
  double overlap(cv::Size size) const {
    std::vector<cv::Point2f> corners{{0, 0},
                                     {static_cast<float>(size.width), 0},
                                     {0, static_cast<float>(size.height)},
                                     {static_cast<float>(size.width), static_cast<float>(size.height)}};
    for (cv::Point2f& c : corners) c = applyModel(to_reference_, c);
    const cv::Rect2f view = cv::boundingRect(corners);
    const cv::Rect2f reference(0, 0, static_cast<float>(size.width), static_cast<float>(size.height));
    return (view & reference).area() / reference.area();
  }

  CameraTracker tracker_;
  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2_ = newMog2();
  cv::Matx33d to_reference_ = cv::Matx33d::eye();
};

}  // namespace

std::unique_ptr<Pipeline> makeMog2Pipeline(const Params& params) {
  return std::make_unique<Mog2Pipeline>(params);
}

std::unique_ptr<Pipeline> makeCompensatedMog2Pipeline(const Params& params) {
  return std::make_unique<CompensatedMog2Pipeline>(params);
}

}  // namespace movseg
