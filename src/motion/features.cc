#include "motion/features.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// |gx| + |gy| of the 3x3 Sobel on 8-bit grey; below this a cell has no edge worth tracking.
constexpr int kMinEdgeGradient = 60;

void addEdgePoints(const cv::Mat& grey, int cell, int margin, std::vector<cv::Point2f>* points) {
  cv::Mat gx, gy, magnitude;
  cv::Sobel(grey, gx, CV_16S, 1, 0);
  cv::Sobel(grey, gy, CV_16S, 0, 1);
  cv::Mat abs_gx = cv::abs(gx), abs_gy = cv::abs(gy);
  cv::add(abs_gx, abs_gy, magnitude, cv::noArray(), CV_32S);
  const cv::Rect inner(margin, margin, grey.cols - 2 * margin, grey.rows - 2 * margin);
  for (int y = inner.y; y < inner.br().y; y += cell) {
    for (int x = inner.x; x < inner.br().x; x += cell) {
      const cv::Rect box = cv::Rect(x, y, cell, cell) & inner;
      double best = 0;
      cv::Point at;
      cv::minMaxLoc(magnitude(box), nullptr, &best, nullptr, &at);
      if (best >= kMinEdgeGradient) points->emplace_back(at + box.tl());
    }
  }
}

}  // namespace

std::vector<cv::Point2f> detectFeatures(const cv::Mat& grey, const Params& params) {
  std::vector<cv::Point2f> points;
  const int margin = params.zncc_window / 2 + 1;
  if (grey.cols <= 2 * margin || grey.rows <= 2 * margin) return points;

  cv::Mat mask = cv::Mat::zeros(grey.size(), CV_8U);
  mask(cv::Rect(margin, margin, grey.cols - 2 * margin, grey.rows - 2 * margin)).setTo(255);
  const double min_distance = std::max(1, params.edge_cell / 2);
  cv::goodFeaturesToTrack(grey, points, params.max_corners, 0.01, min_distance, mask);
  addEdgePoints(grey, params.edge_cell, margin, &points);
  return points;
}

}  // namespace movseg
