#include "motion/motion_debug.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Mat drawMatches(const cv::Mat& grey, const MotionEstimate& motion) {
  cv::Mat canvas;
  if (grey.empty()) return canvas;
  cv::cvtColor(grey, canvas, cv::COLOR_GRAY2BGR);
  for (size_t i = 0; i < motion.matches.size(); ++i) {
    const Track& t = motion.matches[i];
    const cv::Scalar colour = motion.background[i] ? cv::Scalar(255, 0, 0) : cv::Scalar(0, 0, 255);
    cv::line(canvas, t.prev, t.cur, colour, 1, cv::LINE_AA);
    cv::circle(canvas, t.cur, 2, colour, cv::FILLED, cv::LINE_AA);
  }
  return canvas;
}

cv::Mat drawDifference(const cv::Mat& difference) {
  cv::Mat scaled, heat;
  difference.convertTo(scaled, CV_8U, 255.0 / 1024.0);
  cv::applyColorMap(scaled, heat, cv::COLORMAP_INFERNO);
  return heat;
}

}  // namespace movseg
