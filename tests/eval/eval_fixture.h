// Tiny mask folders for the evaluation tests.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace movseg::test {

// A 0 / 255 CV_8U mask of `size` with `foreground` set (an empty rectangle: no foreground).
cv::Mat rectMask(cv::Size size, cv::Rect foreground);

// Writes `image` as folder/name, creating the folder first.
void writeImage(const std::string& folder, const std::string& name, const cv::Mat& image);

// Writes `text` as folder/name, creating the folder first.
void writeText(const std::string& folder, const std::string& name, const std::string& text);

}  // namespace movseg::test
