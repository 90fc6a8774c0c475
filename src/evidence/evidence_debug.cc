#include "evidence/evidence_debug.h"

namespace movseg {

cv::Mat drawResidual(const cv::Mat& residual, float scale) {
  cv::Mat picture;
  residual.convertTo(picture, CV_8U, 128.0 / scale);
  return picture;
}

cv::Mat drawConfirmation(const cv::Mat& confirmation) {
  cv::Mat picture;
  confirmation.convertTo(picture, CV_8U, 127.5, 127.5);
  return picture;
}

cv::Mat drawCarried(const cv::Mat& carried, cv::Size size) {
  return carried.empty() ? cv::Mat(cv::Mat::zeros(size, CV_8U)) : carried.clone();
}

cv::Mat drawLogOdds(const cv::Mat& log_odds) {
  cv::Mat picture;
  log_odds.convertTo(picture, CV_8U, 25.0, 128.0);
  return picture;
}

}  // namespace movseg
