#include "core/black_bars.h"

#include <algorithm>

namespace movseg {
namespace {

constexpr int kBlackMean = 24;  // FFmpeg cropdetect's default limit, for 8 bits
constexpr int kBlackPeak = 64;

// Whether the `count` BGR pixels from `first`, `step` bytes apart, are a bar's line.
bool isBlackLine(const uchar* first, int count, size_t step) {
  long sum = 0;
  for (int i = 0; i < count; ++i) {
    const uchar* p = first + static_cast<size_t>(i) * step;
    const int brightest = std::max({p[0], p[1], p[2]});
    if (brightest > kBlackPeak) return false;
    sum += brightest;
  }
  return sum <= static_cast<long>(kBlackMean) * count;
}

}  // namespace

cv::Rect pictureInsideBlackBars(const cv::Mat& bgr) {
  CV_Assert(bgr.type() == CV_8UC3);
  const int w = bgr.cols, h = bgr.rows;
  const auto row = [&](int y) { return isBlackLine(bgr.ptr(y), w, 3); };
  const auto column = [&](int x) { return isBlackLine(bgr.ptr(0) + 3 * x, h, bgr.step); };
  int top = 0, bottom = h, left = 0, right = w;
  while (top < h && row(top)) ++top;
  while (bottom > top && row(bottom - 1)) --bottom;
  while (left < w && column(left)) ++left;
  while (right > left && column(right - 1)) --right;
  const cv::Rect picture(left, top, right - left, bottom - top);
  if (picture.width * 4 < w || picture.height * 4 < h) return {0, 0, w, h};
  return picture;
}

}  // namespace movseg
