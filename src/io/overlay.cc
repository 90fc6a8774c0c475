#include "io/overlay.h"

#include <opencv2/imgproc.hpp>

#include "classify/classify_debug.h"
#include "core/frame.h"

namespace movseg {

cv::Mat drawOverlay(const cv::Mat& frame, const Result& result, const std::string& hud,
                    bool feature_dots) {
  cv::Mat canvas = toBgr8(frame).clone();
  if (!result.mask.empty()) {
    cv::Mat tint(canvas.size(), CV_8UC3, cv::Scalar(0, 0, 255));
    cv::Mat blended;
    cv::addWeighted(canvas, 0.5, tint, 0.5, 0, blended);
    blended.copyTo(canvas, result.mask);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(result.mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(canvas, contours, -1, cv::Scalar(0, 0, 255), 2, cv::LINE_AA);
  }
  for (const Feature& f : feature_dots ? result.features : std::vector<Feature>()) {
    cv::circle(canvas, f.position, 2, labelColour(f.label), cv::FILLED, cv::LINE_AA);
  }
  if (!hud.empty()) {
    const double scale = std::max(0.4, canvas.cols / 1000.0);
    const cv::Point at(8, static_cast<int>(8 + 20 * scale));
    cv::putText(canvas, hud, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3,
                cv::LINE_AA);
    cv::putText(canvas, hud, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
                cv::LINE_AA);
  }
  return canvas;
}

}  // namespace movseg
