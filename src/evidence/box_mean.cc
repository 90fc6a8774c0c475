#include "evidence/box_mean.h"

#include <opencv2/core/hal/intrin.hpp>

namespace movseg {
namespace {

using cv::v_uint16x8;

constexpr int kSide = 5;
constexpr int kReach = kSide / 2;  // rows and columns on either side of the centre
constexpr int kLanes = 8;          // 16-bit lanes

// Index v of a row or column of n pixels, reflected as cv::blur's default border outside.
int reflected(int v, int n) {
  return v >= 0 && v < n ? v : cv::borderInterpolate(v, n, cv::BORDER_REFLECT_101);
}

// A sum of 25 bytes divided by 25, rounded: floor((sum + 12) / 25), as (sum + 12) * 41944 >> 20
// (41944 / 2^20 exceeds 1/25 by a relative 2.3e-5: under 0.006 at the largest sum, less than the
// 1/25 a quotient's fraction stays below 1 by).
constexpr int kRound = 12, kReciprocal = 41944, kShift = 20;

v_uint16x8 dividedBy25(const v_uint16x8& sum) {
  const v_uint16x8 high = cv::v_mul_hi(sum + cv::v_setall_u16(kRound), cv::v_setall_u16(kReciprocal));
  return cv::v_shr<kShift - 16>(high);
}

uchar dividedBy25(int sum) { return static_cast<uchar>(((sum + kRound) * kReciprocal) >> kShift); }

// The five rows of row `y`'s window summed per column into `sums` (width values).
void sumColumns(const cv::Mat& image, int y, ushort* sums) {
  for (int x = 0; x < image.cols; ++x) sums[x] = 0;
  for (int k = -kReach; k <= kReach; ++k) {
    const uchar* row = image.ptr<uchar>(reflected(y + k, image.rows));
    for (int x = 0; x < image.cols; ++x) sums[x] = static_cast<ushort>(sums[x] + row[x]);
  }
}

// The window's column sums moved down a row: `entering` added, `leaving` taken away.
void slideColumns(const uchar* entering, const uchar* leaving, int width, ushort* sums) {
  int x = 0;
  for (; x + 2 * kLanes <= width; x += 2 * kLanes) {
    v_uint16x8 in_low, in_high, out_low, out_high;
    cv::v_expand(cv::v_load(entering + x), in_low, in_high);
    cv::v_expand(cv::v_load(leaving + x), out_low, out_high);
    // Never below 0 nor above 25 x 255: the saturating 16-bit operations are exact.
    cv::v_store(sums + x, cv::v_load(sums + x) + in_low - out_low);
    cv::v_store(sums + x + kLanes, cv::v_load(sums + x + kLanes) + in_high - out_high);
  }
  for (; x < width; ++x) sums[x] = static_cast<ushort>(sums[x] + entering[x] - leaving[x]);
}

}  // namespace

void BoxMean5::apply(const cv::Mat& image, cv::Mat* mean) {
  CV_Assert(image.type() == CV_8UC1 && !image.empty() && !image.isSubmatrix());
  mean->create(image.size(), CV_8U);
  const int width = image.cols;
  // Room for the reflected columns and for the last vector's loads past them.
  column_sums_.resize(static_cast<size_t>(width + 2 * kReach + kLanes));
  ushort* sums = column_sums_.data() + kReach;  // sums[x] for column x, from -2 to width + 1
  int reflected_columns[2 * kReach];  // what columns -2, -1, width and width + 1 stand for
  for (int k = 0; k < kReach; ++k) {
    reflected_columns[k] = reflected(k - kReach, width);
    reflected_columns[kReach + k] = reflected(width + k, width);
  }
  sumColumns(image, 0, sums);
  for (int y = 0; y < image.rows; ++y) {
    if (y > 0) {
      slideColumns(image.ptr<uchar>(reflected(y + kReach, image.rows)),
                   image.ptr<uchar>(reflected(y - 1 - kReach, image.rows)), width, sums);
    }
    for (int k = 0; k < kReach; ++k) {
      sums[k - kReach] = sums[reflected_columns[k]];
      sums[width + k] = sums[reflected_columns[kReach + k]];
    }
    uchar* out = mean->ptr<uchar>(y);
    int x = 0;
    for (; x + kLanes <= width; x += kLanes) {
      v_uint16x8 window = cv::v_load(sums + x - kReach);
      for (int k = 1; k < kSide; ++k) window += cv::v_load(sums + x - kReach + k);
      cv::v_pack_store(out + x, dividedBy25(window));
    }
    for (; x < width; ++x) {
      int window = 0;
      for (int k = 0; k < kSide; ++k) window += sums[x - kReach + k];
      out[x] = dividedBy25(window);
    }
  }
}

}  // namespace movseg
