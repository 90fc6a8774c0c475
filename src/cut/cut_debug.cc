#include "cut/cut_debug.h"

#include <opencv2/imgproc.hpp>

namespace movseg {

cv::Mat drawConfidence(const cv::Mat& confidence) {
  double max_value = 0;
  cv::minMaxLoc(confidence, nullptr, &max_value);
  cv::Mat scaled, heat;
  confidence.convertTo(scaled, CV_8U, max_value > 0 ? 255.0 / max_value : 0.0);
  cv::applyColorMap(scaled, heat, cv::COLORMAP_VIRIDIS);
  return heat;
}

}  // namespace movseg
