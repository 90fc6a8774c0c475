// Camera models as 3x3 matrices (affine: last row 0 0 1) and the few operations on them.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

inline cv::Point2f applyModel(const cv::Matx33d& m, cv::Point2f p) {
  const double w = m(2, 0) * p.x + m(2, 1) * p.y + m(2, 2);
  return {static_cast<float>((m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2)) / w),
          static_cast<float>((m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2)) / w)};
}

// The same motion in coordinates scaled by `scale` (p' = scale * p): S * m * S^-1.
inline cv::Matx33d rescaleModel(const cv::Matx33d& m, double scale) {
  const cv::Matx33d s(scale, 0, 0, 0, scale, 0, 0, 0, 1);
  const cv::Matx33d s_inv(1 / scale, 0, 0, 0, 1 / scale, 0, 0, 0, 1);
  return s * m * s_inv;
}

inline bool isAffine(const cv::Matx33d& m) {
  return m(2, 0) == 0 && m(2, 1) == 0 && m(2, 2) == 1;
}

}  // namespace movseg
