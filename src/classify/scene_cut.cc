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
    int covered_row = 0, differing_row = 0;  // counts without a branch, which GCC vectorises
    for (int x = 0; x < difference.cols; ++x) {
      const int in = inside[x] != 0;
      covered_row += in;
      differing_row += in & (value[x] > kSceneCutMedianDifference);
    }
    covered_count += covered_row;
    differing += differing_row;
  }
  return isSceneCut(static_cast<long>(difference.total()), covered_count, differing);
}

bool isSceneCut(long total, long covered, long differing) {
  return static_cast<double>(covered) < kSceneCutCoverage * static_cast<double>(total) ||
         differing > covered / 2;
}

}  // namespace movseg
