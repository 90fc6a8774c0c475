#include "classify/scene_cut.h"

#include "motion/compensation.h"

namespace movseg {

bool isSceneCut(const cv::Mat& difference, const cv::Matx33d& model) {
  if (difference.empty()) return false;
  // The pixels the warp of the previous frame reaches, exactly as eq. (4) warped it.
  const cv::Mat covered = warpPrevious(cv::Mat(difference.size(), CV_8U, cv::Scalar(1)),
                                       cv::Mat::zeros(difference.size(), CV_8U), model);
  long covered_count = 0, differing = 0;
  for (int y = 0; y < difference.rows; ++y) {
    const float* value = difference.ptr<float>(y);
    const uchar* inside = covered.ptr<uchar>(y);
    for (int x = 0; x < difference.cols; ++x) {
      covered_count += inside[x] != 0;
      differing += inside[x] != 0 && value[x] > kSceneCutMedianDifference;
    }
  }
  return isSceneCut(static_cast<long>(difference.total()), covered_count, differing);
}

bool isSceneCut(long total, long covered, long differing) {
  return static_cast<double>(covered) < kSceneCutCoverage * static_cast<double>(total) ||
         differing > covered / 2;
}

}  // namespace movseg
