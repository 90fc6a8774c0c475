// cv::remap of an 8-bit image through a CV_32FC2 map with INTER_LINEAR, as OpenCV 4.6 computes
// it, to the bit (tests/evidence/bilinear_remap_test.cc), for a third of its instructions. OpenCV
// - rounds each coordinate to 1/32 pixel, cvRound(x * 32): its integer part saturated to a short,
//   its 5-bit fraction kept;
// - weighs the 2x2 pixels from there by a table of four shorts per pair of fractions (fx, fy):
//   32 (32 - fx)(32 - fy), 32 fx (32 - fy), 32 (32 - fx) fy, 32 fx fy, exactly (products of
//   multiples of 1/32 in float), save at (0, 0), where 32768 does not fit a short and the table
//   holds 32767, 0, 0, 1 (which rounds to the same pixel); the sum rounded, (sum + 2^14) >> 15;
// - reads a tap outside the image at the nearest pixel (BORDER_REPLICATE) or as 0
//   (BORDER_CONSTANT), each of the four on its own.
// Here the weights are the products without the factor 32 and the sum is rounded by
// (sum + 2^9) >> 10, the same values; the image gets two pixels of border on every side, so that
// a coordinate clamped into it reads what OpenCV reads without a test per tap; and each pixel is
// kept beside the one below it, so that the 2x2 pixels are one 4-byte load. Eight points at a
// time in SSE2's lanes; OpenCV converts the map into a buffer first and reads it back.
// Buffers are kept across calls: one object per image size keeps allocating nothing.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

class BilinearRemap {
 public:
  // `image`: CV_8UC1, not empty, sides under 32764 pixels (OpenCV's coordinates are shorts);
  // `border`: cv::BORDER_REPLICATE or cv::BORDER_CONSTANT (with 0). Copied.
  void setSource(const cv::Mat& image, int border);

  // cv::remap(image, *out, map, cv::noArray(), cv::INTER_LINEAR, border) of the source set;
  // `map`: CV_32FC2, of any size. `out` may not share data with the source or the map.
  void remap(const cv::Mat& map, cv::Mat* out) const;

  // remap() of two sources of one size through one map in one pass: each point's place and
  // weights are worked out once for both.
  static void remapBoth(const BilinearRemap& first, const BilinearRemap& second,
                        const cv::Mat& map, cv::Mat* first_out, cv::Mat* second_out);

 private:
  cv::Size size_;
  cv::Mat bordered_;  // the image with its border
  cv::Mat stacked_;   // CV_8UC2: each pixel of bordered_ and the one below it
};

}  // namespace movseg
