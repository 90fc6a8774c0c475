#include "classify/scene_cut.h"

#include <algorithm>
#include <vector>

#include "motion/compensation.h"

namespace movseg {

bool isSceneCut(const cv::Mat& difference, const cv::Matx33d& model) {
  if (difference.empty()) return false;
  // The pixels the warp of the previous frame reaches, exactly as eq. (4) warped it.
  const cv::Mat covered = warpPrevious(cv::Mat(difference.size(), CV_8U, cv::Scalar(1)),
                                       cv::Mat::zeros(difference.size(), CV_8U), model);
  std::vector<float> d;
  d.reserve(difference.total());
  for (int y = 0; y < difference.rows; ++y) {
    const float* value = difference.ptr<float>(y);
    const uchar* inside = covered.ptr<uchar>(y);
    for (int x = 0; x < difference.cols; ++x) {
      if (inside[x] != 0) d.push_back(value[x]);
    }
  }
  const double covered_share =
      static_cast<double>(d.size()) / static_cast<double>(difference.total());
  if (d.empty()) return isSceneCut(covered_share, 0);
  const auto middle = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), middle, d.end());
  return isSceneCut(covered_share, *middle);
}

bool isSceneCut(double covered_share, double median_difference) {
  return covered_share < kSceneCutCoverage || median_difference > kSceneCutMedianDifference;
}

}  // namespace movseg
