#include "classify/scene_cut.h"

#include <algorithm>
#include <vector>

namespace movseg {

bool isSceneCut(const cv::Mat& difference) {
  if (difference.empty()) return false;
  std::vector<float> d;
  d.reserve(difference.total());
  for (int y = 0; y < difference.rows; ++y) {
    const float* row = difference.ptr<float>(y);
    d.insert(d.end(), row, row + difference.cols);
  }
  const auto middle = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), middle, d.end());
  return *middle > kSceneCutMedianDifference;
}

}  // namespace movseg
