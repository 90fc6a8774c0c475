#include "refine/refine_debug.h"

namespace movseg {

cv::Mat drawEdgeSnap(const cv::Mat& bgr, const cv::Mat& cut, const cv::Mat& snapped) {
  cv::Mat picture = bgr * 0.5;
  const cv::Mat moving = snapped > 127;
  picture.setTo(cv::Scalar(160, 160, 160), cut & moving);
  picture.setTo(cv::Scalar(0, 255, 0), moving & ~cut);
  picture.setTo(cv::Scalar(0, 0, 255), cut & ~moving);
  return picture;
}

}  // namespace movseg
