// Segmenter: the paper's flow chart (Fig. 1), one call per frame pair.
#include "movseg/segmenter.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "classify/classify.h"
#include "classify/classify_debug.h"
#include "core/camera_tracker.h"
#include "core/frame.h"
#include "core/timing.h"
#include "cut/cut_debug.h"
#include "cut/graph_cut.h"
#include "motion/compensation.h"
#include "motion/model.h"
#include "motion/motion_debug.h"

namespace movseg {
namespace {

std::vector<cv::Point2f> scaled(const std::vector<cv::Point2f>& points, double scale) {
  std::vector<cv::Point2f> out(points.size());
  const auto s = static_cast<float>(scale);
  std::transform(points.begin(), points.end(), out.begin(), [s](cv::Point2f p) { return p * s; });
  return out;
}

// Scaled down from the alignment scale, a feature by the right or bottom edge can round to the
// pixel past it; the seeds index images of `size`.
std::vector<cv::Point2f> clampedTo(std::vector<cv::Point2f> points, cv::Size size) {
  for (cv::Point2f& p : points) {
    p.x = std::clamp(p.x, 0.f, static_cast<float>(size.width - 1));
    p.y = std::clamp(p.y, 0.f, static_cast<float>(size.height - 1));
  }
  return points;
}

}  // namespace

struct Segmenter::Impl {
  explicit Impl(const Params& p) : params(p), tracker(p) {}
  Params params;
  CameraTracker tracker;
  // The previous frame and the model of the last pair, for compensatedPreviousFrame().
  cv::Mat last_previous, last_current;
  cv::Matx33d last_model = cv::Matx33d::eye();

  Result process(const cv::Mat& frame);
  void classifyAndCut(const PreparedFrame& cur, const MotionEstimate& motion,
                      const cv::Mat& difference, Result* result);
};

Result Segmenter::Impl::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  Result result;
  Diagnostics& diag = result.diagnostics;
  const CameraTracker::Step step = tracker.advance(frame, &diag);  // §3.1
  const PreparedFrame& cur = *step.current;
  last_current = cur.bgr;
  if (step.previous == nullptr) {
    result.mask = cv::Mat::zeros(cur.bgr.size(), CV_8U);
    for (const cv::Point2f& p : scaled(cur.features, 1.0 / cur.align_scale)) {
      result.features.push_back({p, FeatureLabel::kUnknown});
    }
    last_previous.release();
    diag.timings.total_ms = millisecondsSince(start);
    return result;
  }
  last_previous = step.previous->bgr;
  last_model = diag.model;

  // Eq. (4) at the segmentation scale.
  const cv::Matx33d seg_model = rescaleModel(diag.model, cur.seg_scale);
  const cv::Mat difference =
      compensatedDifference(step.previous->seg_smooth, cur.seg_smooth, seg_model);
  if (params.debug_images) {
    result.debug["matches"] = drawMatches(cur.small_grey, step.motion);
    result.debug["difference"] = drawDifference(difference);
  }
  classifyAndCut(cur, step.motion, difference, &result);
  diag.timings.total_ms = millisecondsSince(start);
  return result;
}

// §3.2 and §3.3 on the current frame's features at the segmentation scale.
void Segmenter::Impl::classifyAndCut(const PreparedFrame& cur, const MotionEstimate& motion,
                                     const cv::Mat& difference, Result* result) {
  Diagnostics& diag = result->diagnostics;
  Clock::time_point stage = Clock::now();
  const std::vector<cv::Point2f> points =
      clampedTo(scaled(cur.features, cur.seg_scale / cur.align_scale), cur.seg_bgr.size());
  diag.lambda = chooseLambda(difference, staticPoints(motion, cur, cur.seg_scale), params);
  std::vector<FeatureLabel> labels = classifyByDifference(difference, points, diag.lambda);
  if (params.debug_images) result->debug["features"] = drawFeatures(cur.seg_bgr, points, labels);
  if (params.gmm_refine) {
    std::vector<cv::Vec3f> colours;
    for (const cv::Point2f& p : points) colours.emplace_back(cur.seg_bgr.at<cv::Vec3b>(p));
    refineByColour(colours, params.gmm_clusters, &labels);
  }
  if (params.debug_images) {
    result->debug["features_refined"] = drawFeatures(cur.seg_bgr, points, labels);
  }
  std::vector<cv::Point> fg, bg;
  for (size_t i = 0; i < points.size(); ++i) {
    const cv::Point p(cvRound(points[i].x), cvRound(points[i].y));
    if (labels[i] == FeatureLabel::kForeground) fg.push_back(p);
    if (labels[i] == FeatureLabel::kBackground) bg.push_back(p);
    result->features.push_back({points[i] * static_cast<float>(1.0 / cur.seg_scale), labels[i]});
  }
  diag.foreground_seeds = static_cast<int>(fg.size());
  diag.background_seeds = static_cast<int>(bg.size());
  diag.unknown_seeds = static_cast<int>(points.size() - fg.size() - bg.size());
  diag.timings.classify_ms = millisecondsSince(stage);

  stage = Clock::now();
  cv::Mat mask;
  if (fg.empty()) {
    mask = cv::Mat::zeros(cur.seg_bgr.size(), CV_8U);
  } else if (bg.empty()) {
    // Everything that has seeds moves: the cut has nothing to oppose, eq. (3) alone decides.
    diag.no_background_seeds = true;
    mask = difference > diag.lambda;
  } else {
    CutResult cut = geodesicGraphCut(cur.seg_bgr, fg, bg, params);
    mask = cut.mask;
    diag.cut_nodes = cut.graph_nodes;
    if (params.debug_images) result->debug["confidence"] = drawConfidence(cut.confidence);
  }
  result->mask = upscaledMask(mask, cur.bgr.size());
  if (params.debug_images) result->debug["mask"] = result->mask;
  diag.timings.cut_ms = millisecondsSince(stage);
}

Segmenter::Segmenter(const Params& params) {
  params.check();
  impl_ = std::make_unique<Impl>(params);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) { return impl_->process(frame); }

void Segmenter::reset() {
  impl_->tracker.reset();
  impl_->last_previous.release();
}

cv::Mat Segmenter::compensatedPreviousFrame() const {
  if (impl_->last_previous.empty()) return cv::Mat();
  return warpPrevious(impl_->last_previous, impl_->last_current, impl_->last_model);
}

const Params& Segmenter::params() const { return impl_->params; }

}  // namespace movseg
