#include "classify/classify.h"

#include <algorithm>

#include "classify/colour_gmm.h"

namespace movseg {

namespace {

float differenceAt(const cv::Mat& difference, cv::Point2f p) {
  const int x = std::clamp(cvRound(p.x), 0, difference.cols - 1);
  const int y = std::clamp(cvRound(p.y), 0, difference.rows - 1);
  return difference.at<float>(y, x);
}

}  // namespace

double chooseLambda(const cv::Mat& difference, const std::vector<cv::Point2f>& static_points,
                    const Params& params) {
  if (static_points.empty()) return params.lambda;
  std::vector<float> values;
  values.reserve(static_points.size());
  for (const cv::Point2f& p : static_points) values.push_back(differenceAt(difference, p));
  const auto q75 = values.begin() + static_cast<std::ptrdiff_t>(values.size() * 3 / 4);
  std::nth_element(values.begin(), q75, values.end());
  return std::max(params.lambda, params.lambda_residual_factor * static_cast<double>(*q75));
}

std::vector<FeatureLabel> classifyByDifference(const cv::Mat& difference,
                                               const std::vector<cv::Point2f>& points,
                                               double lambda) {
  std::vector<FeatureLabel> labels;
  labels.reserve(points.size());
  for (const cv::Point2f& p : points) {
    labels.push_back(differenceAt(difference, p) > lambda ? FeatureLabel::kForeground
                                                          : FeatureLabel::kBackground);
  }
  return labels;
}

void refineByColour(const std::vector<cv::Vec3f>& colours, int clusters,
                    std::vector<FeatureLabel>* labels) {
  std::vector<cv::Vec3f> fg, bg;
  for (size_t i = 0; i < colours.size(); ++i) {
    if ((*labels)[i] == FeatureLabel::kForeground) fg.push_back(colours[i]);
    if ((*labels)[i] == FeatureLabel::kBackground) bg.push_back(colours[i]);
  }
  if (fg.empty() || bg.empty()) return;
  const ColourGmm fg_model = ColourGmm::fit(fg, clusters);
  const ColourGmm bg_model = ColourGmm::fit(bg, clusters);
  for (size_t i = 0; i < colours.size(); ++i) {
    FeatureLabel& label = (*labels)[i];
    // P_f <= P_b  <=>  p_f <= p_b  <=>  log p_f <= log p_b.
    const double log_f = fg_model.logLikelihood(colours[i]);
    const double log_b = bg_model.logLikelihood(colours[i]);
    if (label == FeatureLabel::kForeground && log_f <= log_b) label = FeatureLabel::kUnknown;
    if (label == FeatureLabel::kBackground && log_f >= log_b) label = FeatureLabel::kUnknown;
  }
}

FeatureClasses classifyFeatures(const cv::Mat& difference, const cv::Mat& bgr,
                                const std::vector<cv::Point2f>& points,
                                const std::vector<cv::Point2f>& static_points,
                                const Params& params) {
  FeatureClasses classes;
  classes.lambda = chooseLambda(difference, static_points, params);
  classes.by_difference = classifyByDifference(difference, points, classes.lambda);
  classes.labels = classes.by_difference;
  if (params.gmm_refine) {
    std::vector<cv::Vec3f> colours;
    colours.reserve(points.size());
    for (const cv::Point2f& p : points) colours.emplace_back(bgr.at<cv::Vec3b>(p));
    refineByColour(colours, params.gmm_clusters, &classes.labels);
  }
  return classes;
}

}  // namespace movseg
