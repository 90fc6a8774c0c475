#include "motion/support.h"

#include <algorithm>
#include <bitset>

namespace movseg {

CoverageSupportMeasurer::CoverageSupportMeasurer(const std::vector<cv::Point2f>& points,
                                                 cv::Size image_size) {
  reset(points, image_size);
}

void CoverageSupportMeasurer::reset(const std::vector<cv::Point2f>& points, cv::Size image_size) {
  cell_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const int cx = std::clamp(static_cast<int>(points[i].x * kGrid / image_size.width), 0, kGrid - 1);
    const int cy = std::clamp(static_cast<int>(points[i].y * kGrid / image_size.height), 0, kGrid - 1);
    cell_[i] = cy * kGrid + cx;
  }
}

CoverageSupportMeasurer::Support CoverageSupportMeasurer::evaluate(
    const std::vector<double>& residuals, double max_residual) const {
  std::bitset<kGrid * kGrid> covered;
  Support support;
  for (size_t i = 0; i < residuals.size(); ++i) {
    if (residuals[i] > max_residual) continue;
    ++support.num_inliers;
    covered.set(static_cast<size_t>(cell_[i]));
  }
  support.cells = static_cast<int>(covered.count());
  return support;
}

}  // namespace movseg
