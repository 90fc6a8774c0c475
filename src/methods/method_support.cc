#include "methods/method_support.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Mat upscaledMask(const cv::Mat& mask, cv::Size size) {
  if (mask.size() == size) return mask;
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_LINEAR);
  cv::threshold(out, out, 127, 255, cv::THRESH_BINARY);
  return out;
}

}  // namespace movseg
