#include "synth/raster.h"

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// Fractional bits of the vertices given to fillPoly: shapes move in 1/16-pixel steps.
constexpr int kShift = 4;
constexpr int kUnit = 1 << kShift;

}  // namespace

Coverage polygonCoverage(const std::vector<cv::Point2d>& polygon, cv::Size frame_size) {
  std::vector<cv::Point> fixed_points;
  for (const cv::Point2d& p : polygon)
    fixed_points.emplace_back(cvRound(p.x * kUnit), cvRound(p.y * kUnit));
  const cv::Rect fixed = cv::boundingRect(fixed_points);
  const double to_pixels = 1.0 / kUnit;
  const cv::Point top_left(cvFloor(fixed.x * to_pixels) - 1, cvFloor(fixed.y * to_pixels) - 1);
  const cv::Point bottom_right(cvCeil(fixed.br().x * to_pixels) + 1,
                               cvCeil(fixed.br().y * to_pixels) + 1);
  Coverage coverage;
  coverage.box = cv::Rect(top_left, bottom_right) & cv::Rect(cv::Point(0, 0), frame_size);
  if (coverage.box.empty()) return coverage;
  for (cv::Point& p : fixed_points) p -= cv::Point(coverage.box.x * kUnit, coverage.box.y * kUnit);
  coverage.shape = cv::Mat::zeros(coverage.box.size(), CV_8U);
  cv::fillPoly(coverage.shape, std::vector<std::vector<cv::Point>>{fixed_points}, cv::Scalar(255),
               cv::LINE_8, kShift);
  return coverage;
}

}  // namespace movseg
