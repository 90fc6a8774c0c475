// cv::blur(image, mean, cv::Size(5, 5)) of an 8-bit image, as OpenCV 4.6 computes it, to the bit
// (tests/evidence/box_mean_test.cc), for about a quarter of its instructions. OpenCV sums the
// 5x5 window in 16 bits, borders reflected (BORDER_REFLECT_101), and divides by 25 in fixed
// point, ((sum + 13) * 335544) >> 23, which is the sum divided by 25 rounded to nearest for every
// sum of 25 bytes (none is a tie). Here the window's column sums slide down a row at a time (the
// row entering added, the one leaving taken away, 16 columns at once), five of them are added
// per pixel, 8 at once, and the division is (sum + 12) * 41944 >> 20, the same rounded quotient,
// in 16-bit lanes.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

class BoxMean5 {
 public:
  // `image`: CV_8UC1, not empty, and not a view into a larger image (cv::blur reads the pixels
  // around a view for its border); `mean` is made CV_8UC1 of its size, not sharing its data.
  void apply(const cv::Mat& image, cv::Mat* mean);

 private:
  std::vector<ushort> column_sums_;  // one row's, with two reflected columns on either side
};

}  // namespace movseg
