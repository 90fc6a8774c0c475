#include "classify/classify_debug.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Mat drawFeatures(const cv::Mat& bgr, const std::vector<cv::Point2f>& points,
                     const std::vector<FeatureLabel>& labels) {
  cv::Mat canvas = bgr.clone();
  for (size_t i = 0; i < points.size(); ++i) {
    cv::Scalar colour(0, 255, 255);
    if (labels[i] == FeatureLabel::kForeground) colour = cv::Scalar(0, 0, 255);
    if (labels[i] == FeatureLabel::kBackground) colour = cv::Scalar(255, 0, 0);
    cv::circle(canvas, points[i], 2, colour, cv::FILLED, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace movseg
