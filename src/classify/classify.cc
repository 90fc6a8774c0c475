#include "classify/classify.h"

#include <algorithm>

#include "classify/colour_gmm.h"

namespace movseg {

double chooseLambda(const cv::Mat& difference, const Params& params) {
  // Median over a regular subsample: exact enough, and O(n / 16).
  std::vector<float> values;
  for (int y = 0; y < difference.rows; y += 4) {
    const float* row = difference.ptr<float>(y);
    for (int x = 0; x < difference.cols; x += 4) values.push_back(row[x]);
  }
  if (values.empty()) return params.lambda;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return std::max(params.lambda, params.lambda_noise_factor * static_cast<double>(*mid));
}

std::vector<FeatureLabel> classifyByDifference(const cv::Mat& difference,
                                               const std::vector<cv::Point2f>& points,
                                               double lambda) {
  std::vector<FeatureLabel> labels;
  labels.reserve(points.size());
  for (const cv::Point2f& p : points) {
    const int x = std::clamp(cvRound(p.x), 0, difference.cols - 1);
    const int y = std::clamp(cvRound(p.y), 0, difference.rows - 1);
    labels.push_back(difference.at<float>(y, x) > lambda ? FeatureLabel::kForeground
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

}  // namespace movseg
