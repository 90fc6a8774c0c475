// `paper`: the publication's pipeline, as its Fig. 1 draws it — camera motion compensation
// (§3.1), feature classification (§3.2), geodesic graph cut (§3.3) — on two frames at a time.
#include <algorithm>

#include "classify/classify.h"
#include "classify/classify_debug.h"
#include "core/timing.h"
#include "cut/cut_debug.h"
#include "cut/graph_cut.h"
#include "cut/grid_max_flow.h"
#include "motion/camera_tracker.h"
#include "motion/motion_debug.h"
#include "pipelines/pipeline.h"
#include "pipelines/tracked.h"

namespace movseg {
namespace {

// The current frame's features at the segmentation scale. Scaled down from the alignment
// scale, a feature by the right or bottom edge can round to the pixel past it; the seeds index
// images of the segmentation size.
std::vector<cv::Point2f> featuresAtSegmentationScale(const TrackedFrame& frame) {
  const PreparedFrame& image = frame.image;
  const auto s = static_cast<float>(image.seg_scale / image.align_scale);
  const cv::Size size = image.seg_bgr.size();
  std::vector<cv::Point2f> points;
  points.reserve(frame.alignment.features.size());
  for (const cv::Point2f& feature : frame.alignment.features) {
    const cv::Point2f p = feature * s;
    points.emplace_back(std::clamp(p.x, 0.f, static_cast<float>(size.width - 1)),
                        std::clamp(p.y, 0.f, static_cast<float>(size.height - 1)));
  }
  return points;
}

struct Seeds {
  std::vector<cv::Point> foreground, background;
};

Seeds seedsOf(const std::vector<cv::Point2f>& points, const std::vector<FeatureLabel>& labels) {
  Seeds seeds;
  for (size_t i = 0; i < points.size(); ++i) {
    const cv::Point p(cvRound(points[i].x), cvRound(points[i].y));
    if (labels[i] == FeatureLabel::kForeground) seeds.foreground.push_back(p);
    if (labels[i] == FeatureLabel::kBackground) seeds.background.push_back(p);
  }
  return seeds;
}

std::vector<Feature> labelledFeatures(const std::vector<cv::Point2f>& points,
                                      const std::vector<FeatureLabel>& labels, double scale) {
  std::vector<Feature> features;
  features.reserve(points.size());
  const auto to_full = static_cast<float>(1.0 / scale);
  for (size_t i = 0; i < points.size(); ++i) features.push_back({points[i] * to_full, labels[i]});
  return features;
}

class PaperPipeline : public Pipeline {
 public:
  explicit PaperPipeline(const Params& params) : params_(params), tracker_(params) {}

  std::unique_ptr<Analysis> newAnalysis() const override {
    return std::make_unique<TrackedAnalysis>();
  }

  void analyse(const cv::Mat& bgr, Analysis* analysis) override {  // §3.1
    analyseTracked(&tracker_, bgr, analysis);
  }

  cv::Mat segment(const Analysis& analysis, const DebugSink& debug, Result* result) override {
    const CameraTracker::Step& step = static_cast<const TrackedAnalysis&>(analysis).step;
    describeMotion(step, &result->diagnostics);
    const TrackedFrame& cur = *step.current;
    if (step.previous == nullptr) {
      const std::vector<FeatureLabel> unknown(cur.alignment.features.size(), FeatureLabel::kUnknown);
      result->features = labelledFeatures(cur.alignment.features, unknown, cur.image.align_scale);
      return cv::Mat::zeros(cur.image.bgr.size(), CV_8U);
    }
    debug.put("matches", [&] { return drawMatches(cur.alignment.grey, step.motion); });
    return classifyAndCut(step, debug, result);
  }

  void reset() override { tracker_.reset(); }

  cv::Mat compensatedPreviousFrame() const override { return tracker_.compensatedPreviousFrame(); }

 private:
  // §3.2 and §3.3 at the segmentation scale.
  cv::Mat classifyAndCut(const CameraTracker::Step& step, const DebugSink& debug, Result* result) {
    const PreparedFrame& cur = step.current->image;
    Diagnostics& diag = result->diagnostics;
    Clock::time_point start = Clock::now();
    const cv::Mat difference = compensatedDifferenceOf(step, debug, &diag);  // eq. (4)
    const std::vector<cv::Point2f> points = featuresAtSegmentationScale(*step.current);
    const FeatureClasses classes = classifyFeatures(
        difference, cur.seg_bgr, points, step.staticPoints(cur.seg_scale), params_);
    debug.put("features", [&] { return drawFeatures(cur.seg_bgr, points, classes.by_difference); });
    debug.put("features_refined", [&] { return drawFeatures(cur.seg_bgr, points, classes.labels); });
    result->features = labelledFeatures(points, classes.labels, cur.seg_scale);
    const Seeds seeds = seedsOf(points, classes.labels);
    diag.classify_ms = millisecondsSince(start);

    start = Clock::now();
    cv::Mat mask;
    int cut_nodes = 0;
    if (seeds.foreground.empty()) {
      mask = cv::Mat::zeros(cur.seg_bgr.size(), CV_8U);
    } else if (seeds.background.empty()) {
      mask = difference > classes.lambda;  // nothing to oppose the cut: eq. (3) alone decides
    } else {
      const CutResult cut = geodesicGraphCut(cur.seg_bgr, seeds.foreground, seeds.background,
                                             params_, MaxFlowSolver::kGrid, &max_flow_);
      debug.put("confidence", [&] { return drawConfidence(cut.confidence); });
      mask = cut.mask;
      cut_nodes = cut.graph_nodes;
    }
    diag.cut_ms = millisecondsSince(start);
    describe(classes, seeds, cut_nodes, &diag);
    return mask;
  }

  static void describe(const FeatureClasses& classes, const Seeds& seeds, int cut_nodes,
                       Diagnostics* diag) {
    diag->lambda = classes.lambda;
    diag->foreground_seeds = static_cast<int>(seeds.foreground.size());
    diag->background_seeds = static_cast<int>(seeds.background.size());
    diag->unknown_seeds = static_cast<int>(classes.labels.size()) - diag->foreground_seeds -
                          diag->background_seeds;
    diag->no_background_seeds = !seeds.foreground.empty() && seeds.background.empty();
    diag->cut_nodes = cut_nodes;
  }

  Params params_;
  CameraTracker tracker_;
  GridMaxFlow max_flow_;
};

}  // namespace

std::unique_ptr<Pipeline> makePaperPipeline(const Params& params) {
  return std::make_unique<PaperPipeline>(params);
}

}  // namespace movseg
