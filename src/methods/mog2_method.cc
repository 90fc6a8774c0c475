#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

#include "core/camera_tracker.h"
#include "methods/baselines.h"
#include "methods/method_support.h"
#include "motion/model.h"

namespace movseg {
namespace {

// OpenCV's defaults (history 500, variance threshold 16) without shadow labels: the masks are
// binary like every other method's.
cv::Ptr<cv::BackgroundSubtractorMOG2> newMog2() {
  return cv::createBackgroundSubtractorMOG2(500, 16.0, false);
}

// Both MOG2 methods run at the segmentation scale, like the paper's cut, so the comparison is
// of methods rather than of resolutions.
class Mog2Method : public Method {
 public:
  explicit Mog2Method(const Params& params) : params_(params), mog2_(newMog2()) {}

  Result process(const cv::Mat& frame) override {
    const Clock::time_point start = Clock::now();
    const cv::Mat bgr = toBgr8(frame);
    Result result;
    if (bgr.size() != size_) {  // a new stream: MOG2 cannot mix sizes
      mog2_ = newMog2();
      result.diagnostics.reset = !size_.empty();
      size_ = bgr.size();
    }
    cv::Mat mask;
    mog2_->apply(resizedTo(bgr, scaledSize(bgr.size(), params_.segmentation_width)), mask);
    result.mask = upscaledMask(mask, bgr.size());
    result.diagnostics.timings.total_ms = millisecondsSince(start);
    return result;
  }

 private:
  Params params_;
  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2_;
  cv::Size size_;
};

// MOG2 in a stabilised reference frame. to_reference_ maps current segmentation-scale pixels
// to the reference's; when less than half of the current view still falls on the reference
// (the camera has panned away), the reference restarts at the current frame.
class CompensatedMog2Method : public TrackedMethod {
 public:
  using TrackedMethod::TrackedMethod;

 protected:
  cv::Mat maskFor(const CameraTracker::Step& step, Diagnostics* diag) override {
    const PreparedFrame& cur = *step.current;
    const cv::Size size = cur.seg_bgr.size();
    if (step.previous == nullptr) {
      restart();
    } else {
      // previous -> current, so current -> reference is (previous -> reference) * inverse.
      to_reference_ = to_reference_ * rescaleModel(diag->model, cur.seg_scale).inv();
      if (overlap(size) < 0.5) restart();
    }
    cv::Mat stabilised, mask_reference, mask;
    cv::warpPerspective(cur.seg_bgr, stabilised, cv::Mat(to_reference_), size);
    mog2_->apply(stabilised, mask_reference);
    cv::warpPerspective(mask_reference, mask, cv::Mat(to_reference_), size,
                        cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
    return mask;
  }

 private:
  void restart() {
    mog2_ = newMog2();
    to_reference_ = cv::Matx33d::eye();
  }

  // Share of the current view's corners' bounding box that lies inside the reference frame.
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

  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2_ = newMog2();
  cv::Matx33d to_reference_ = cv::Matx33d::eye();
};

}  // namespace

std::unique_ptr<Method> makeMog2Method(const Params& params) {
  params.check();
  return std::make_unique<Mog2Method>(params);
}

std::unique_ptr<Method> makeCompensatedMog2Method(const Params& params) {
  params.check();
  return std::make_unique<CompensatedMog2Method>(params);
}

}  // namespace movseg
