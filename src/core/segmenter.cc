// Segmenter: the paper's flow chart (Fig. 1), one call per frame pair.
#include "movseg/segmenter.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "classify/classify.h"
#include "classify/classify_debug.h"
#include "core/frame.h"
#include "cut/cut_debug.h"
#include "cut/graph_cut.h"
#include "motion/compensation.h"
#include "motion/model.h"
#include "motion/motion_debug.h"

namespace movseg {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<cv::Point2f> scaled(const std::vector<cv::Point2f>& points, double scale) {
  std::vector<cv::Point2f> out(points.size());
  const auto s = static_cast<float>(scale);
  std::transform(points.begin(), points.end(), out.begin(), [s](cv::Point2f p) { return p * s; });
  return out;
}

cv::Mat upscaledMask(const cv::Mat& mask, cv::Size size) {
  if (mask.size() == size) return mask;
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_LINEAR);
  cv::threshold(out, out, 127, 255, cv::THRESH_BINARY);
  return out;
}

}  // namespace

struct Segmenter::Impl {
  Params params;
  std::optional<PreparedFrame> previous;
  cv::Matx33d warm_model = cv::Matx33d::eye();  // alignment scale
  // The previous frame and the model of the last pair, for compensatedPreviousFrame().
  std::pair<cv::Mat, cv::Matx33d> last_pair;
  std::uint64_t pairs = 0;

  Result process(const cv::Mat& frame);
  Result firstFrame(PreparedFrame cur, Result result);
  void classifyAndCut(const PreparedFrame& cur, const cv::Mat& difference, Result* result);
};

Result Segmenter::Impl::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  const cv::Mat bgr = toBgr8(frame);
  Result result;
  Diagnostics& diag = result.diagnostics;
  if (previous && previous->bgr.size() != bgr.size()) {
    previous.reset();
    diag.reset = true;
  }
  PreparedFrame cur = prepareFrame(bgr, params);
  diag.timings.prepare_ms = millisecondsSince(start);
  if (!previous) {
    result = firstFrame(std::move(cur), std::move(result));
    result.diagnostics.timings.total_ms = millisecondsSince(start);
    return result;
  }

  // §3.1 camera motion compensation.
  Clock::time_point stage = Clock::now();
  MotionEstimate motion;
  if (!params.static_camera) {
    motion = estimateCameraMotion(*previous, cur, warm_model, params, params.seed + pairs);
    if (!motion.fallback) warm_model = motion.model;
  }
  ++pairs;
  diag.model = rescaleModel(motion.model, 1.0 / cur.align_scale);
  diag.model_is_affine = isAffine(diag.model);
  diag.features = motion.features;
  diag.tracks = motion.tracks;
  diag.matches = static_cast<int>(motion.matches.size());
  diag.background_matches =
      static_cast<int>(std::count(motion.background.begin(), motion.background.end(), 1));
  diag.foreground_matches = diag.matches - diag.background_matches;
  diag.outer_iterations = motion.outer_iterations;
  diag.motion_fallback = motion.fallback && !params.static_camera;
  diag.timings.motion_ms = millisecondsSince(stage);

  // Eq. (4) at the segmentation scale.
  stage = Clock::now();
  const cv::Matx33d seg_model = rescaleModel(diag.model, cur.seg_scale);
  const cv::Mat difference =
      compensatedDifference(previous->seg_smooth, cur.seg_smooth, seg_model);
  last_pair = {previous->bgr, diag.model};
  if (params.debug_images) {
    result.debug["matches"] = drawMatches(cur.small_grey, motion);
    result.debug["difference"] = drawDifference(difference);
  }
  classifyAndCut(cur, difference, &result);
  diag.timings.total_ms = millisecondsSince(start);
  previous = std::move(cur);
  return result;
}

Result Segmenter::Impl::firstFrame(PreparedFrame cur, Result result) {
  result.diagnostics.first_frame = true;
  result.mask = cv::Mat::zeros(cur.bgr.size(), CV_8U);
  for (const cv::Point2f& p : scaled(cur.features, 1.0 / cur.align_scale)) {
    result.features.push_back({p, FeatureLabel::kUnknown});
  }
  last_pair.first.release();
  warm_model = cv::Matx33d::eye();
  previous = std::move(cur);
  return result;
}

// §3.2 and §3.3 on the current frame's features at the segmentation scale.
void Segmenter::Impl::classifyAndCut(const PreparedFrame& cur, const cv::Mat& difference,
                                     Result* result) {
  Diagnostics& diag = result->diagnostics;
  Clock::time_point stage = Clock::now();
  const std::vector<cv::Point2f> points = scaled(cur.features, cur.seg_scale / cur.align_scale);
  diag.lambda = chooseLambda(difference, params);
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

Segmenter::Segmenter(const Params& params) : impl_(std::make_unique<Impl>()) {
  params.check();
  impl_->params = params;
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) { return impl_->process(frame); }

void Segmenter::reset() {
  impl_->previous.reset();
  impl_->last_pair.first.release();
  impl_->warm_model = cv::Matx33d::eye();
}

cv::Mat Segmenter::compensatedPreviousFrame() const {
  const auto& [frame, model] = impl_->last_pair;
  if (frame.empty() || !impl_->previous) return cv::Mat();
  return warpPrevious(frame, impl_->previous->bgr, model);
}

const Params& Segmenter::params() const { return impl_->params; }

}  // namespace movseg
