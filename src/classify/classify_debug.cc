#include "classify/classify_debug.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Scalar labelColour(FeatureLabel label) {
  switch (label) {
    case FeatureLabel::kForeground: return cv::Scalar(0, 0, 255);
    case FeatureLabel::kBackground: return cv::Scalar(255, 128, 0);  // light enough on dark ground
    case FeatureLabel::kUnknown: break;
  }
  return cv::Scalar(0, 255, 255);
}

cv::Mat drawFeatures(const cv::Mat& bgr, const std::vector<cv::Point2f>& points,
                     const std::vector<FeatureLabel>& labels) {
  cv::Mat canvas = bgr.clone();
  for (size_t i = 0; i < points.size(); ++i) {
    cv::circle(canvas, points[i], 2, labelColour(labels[i]), cv::FILLED, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace movseg
