#include "eval/eval_fixture.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

namespace movseg::test {

cv::Mat rectMask(cv::Size size, cv::Rect foreground) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8U);
  mask(foreground).setTo(255);
  return mask;
}

void writeImage(const std::string& folder, const std::string& name, const cv::Mat& image) {
  std::filesystem::create_directories(folder);
  if (!cv::imwrite(folder + "/" + name, image)) {
    throw std::runtime_error("cannot write test image " + folder + "/" + name);
  }
}

void writeText(const std::string& folder, const std::string& name, const std::string& text) {
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "/" + name) << text;
}

}  // namespace movseg::test
