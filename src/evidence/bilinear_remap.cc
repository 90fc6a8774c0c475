#include "evidence/bilinear_remap.h"

#include <algorithm>

#include <opencv2/core/hal/intrin.hpp>

namespace movseg {
namespace {

using cv::v_float32x4;
using cv::v_int16x8;
using cv::v_int32x4;
using cv::v_uint16x8;
using cv::v_uint8x16;

constexpr int kFractionBits = 5;  // OpenCV's INTER_BITS: 1/32 pixel
constexpr int kFractions = 1 << kFractionBits;
constexpr int kBorder = 2;   // around the source: where the clamped coordinates read
constexpr int kPoints = 8;   // a group: two vectors of four floats per coordinate
constexpr int kMaxSide = 32767 - 2 * kBorder;  // offsets in the stacked image are shorts' products

// The weights of a point along one axis, 32 - f and f for its fraction f, as two shorts in each
// 32-bit lane (32 - f in the low one): 32 + f * 65536 - f.
v_int32x4 axisWeights(const v_int32x4& fraction) {
  return cv::v_setall_s32(kFractions) + cv::v_shl<16>(fraction) - fraction;
}

// Four interpolated pixels from their 2x2 neighbourhoods, the bytes p00 p10 p01 p11 per point (pYX,
// Y down), and their weights along x and y (axisWeights): the columns weighed along y, then the two
// sums along x, rounded.
v_int32x4 interpolated(const v_uint8x16& neighbourhoods, const v_int32x4& along_x,
                       const v_int32x4& along_y) {
  v_uint16x8 first, second;  // points 0 and 1, 2 and 3
  cv::v_expand(neighbourhoods, first, second);
  v_int32x4 y_first, y_second;  // each point's weights along y, twice: one per column
  cv::v_zip(along_y, along_y, y_first, y_second);
  const v_int16x8 columns =
      cv::v_pack(cv::v_dotprod(cv::v_reinterpret_as_s16(first), cv::v_reinterpret_as_s16(y_first)),
                 cv::v_dotprod(cv::v_reinterpret_as_s16(second),
                               cv::v_reinterpret_as_s16(y_second)));  // each under 255 * 32
  const v_int32x4 sum = cv::v_dotprod(columns, cv::v_reinterpret_as_s16(along_x));
  return cv::v_shr<2 * kFractionBits>(sum + cv::v_setall_s32(1 << (2 * kFractionBits - 1)));
}

// What the points of a map are read against: the source's pixel (0, 0) in the stacked image,
// its row step there, and the bounds coordinates are clamped to.
struct Source {
  const short* origin;
  v_int16x8 per_xy;  // (1, step) per point: the offset of (x, y) is x + y * step
  v_int16x8 max_x, max_y;
};

// Eight points of a map (x, y, x, y, ...) into eight pixels.
void remapEight(const Source& source, const float* points, uchar* out) {
  // OpenCV's fixed point: the coordinates times 32, rounded to nearest even (NaN and what
  // overflows become INT_MIN, as with cvRound); the integer parts saturated to shorts.
  const v_float32x4 scale = cv::v_setall_f32(static_cast<float>(kFractions));
  v_float32x4 x0, y0, x1, y1;
  cv::v_load_deinterleave(points, x0, y0);
  cv::v_load_deinterleave(points + 2 * 4, x1, y1);
  const v_int32x4 fixed_x0 = cv::v_round(x0 * scale), fixed_y0 = cv::v_round(y0 * scale);
  const v_int32x4 fixed_x1 = cv::v_round(x1 * scale), fixed_y1 = cv::v_round(y1 * scale);
  v_int16x8 ix = cv::v_pack(cv::v_shr<kFractionBits>(fixed_x0), cv::v_shr<kFractionBits>(fixed_x1));
  v_int16x8 iy = cv::v_pack(cv::v_shr<kFractionBits>(fixed_y0), cv::v_shr<kFractionBits>(fixed_y1));
  // Clamped into the border: from -2 both taps are outside on that side, as from further out;
  // from the width (height) on, both are past the last pixel.
  const v_int16x8 low = cv::v_setall_s16(static_cast<short>(-kBorder));
  ix = cv::v_min(cv::v_max(ix, low), source.max_x);
  iy = cv::v_min(cv::v_max(iy, low), source.max_y);

  // The 2x2 neighbourhoods, one 4-byte load each from its offset.
  v_int16x8 xy0, xy1;
  cv::v_zip(ix, iy, xy0, xy1);
  int CV_DECL_ALIGNED(16) offsets[kPoints];
  cv::v_store_aligned(offsets, cv::v_dotprod(xy0, source.per_xy));
  cv::v_store_aligned(offsets + 4, cv::v_dotprod(xy1, source.per_xy));
  const v_uint8x16 first = cv::v_reinterpret_as_u8(cv::v_lut_pairs(source.origin, offsets));
  const v_uint8x16 second = cv::v_reinterpret_as_u8(cv::v_lut_pairs(source.origin, offsets + 4));

  const v_int32x4 mask = cv::v_setall_s32(kFractions - 1);
  const v_int32x4 value0 = interpolated(first, axisWeights(fixed_x0 & mask),
                                        axisWeights(fixed_y0 & mask));
  const v_int32x4 value1 = interpolated(second, axisWeights(fixed_x1 & mask),
                                        axisWeights(fixed_y1 & mask));
  cv::v_pack_u_store(out, cv::v_pack(value0, value1));
}

}  // namespace

void BilinearRemap::setSource(const cv::Mat& image, int border) {
  CV_Assert(image.type() == CV_8UC1 && !image.empty());
  CV_Assert(image.cols <= kMaxSide && image.rows <= kMaxSide);
  CV_Assert(border == cv::BORDER_REPLICATE || border == cv::BORDER_CONSTANT);
  size_ = image.size();
  // Isolated: a view into a larger image is extended as an image of its own, as cv::remap reads it.
  cv::copyMakeBorder(image, bordered_, kBorder, kBorder, kBorder, kBorder,
                     border | cv::BORDER_ISOLATED, cv::Scalar(0));
  // Row r of stacked_ pairs rows r and r + 1 of bordered_: the last row has none below it.
  const cv::Mat pair[] = {bordered_.rowRange(0, bordered_.rows - 1),
                          bordered_.rowRange(1, bordered_.rows)};
  cv::merge(pair, 2, stacked_);
}

void BilinearRemap::remap(const cv::Mat& map, cv::Mat* out) const {
  CV_Assert(map.type() == CV_32FC2 && !stacked_.empty());
  out->create(map.size(), CV_8U);
  const auto step = static_cast<int>(stacked_.step1() / 2);
  const Source source{reinterpret_cast<const short*>(stacked_.ptr(kBorder)) + kBorder,
                      cv::v_reinterpret_as_s16(cv::v_setall_s32(1 + step * 65536)),
                      cv::v_setall_s16(static_cast<short>(size_.width)),
                      cv::v_setall_s16(static_cast<short>(size_.height))};
  for (int y = 0; y < map.rows; ++y) {
    const float* points = map.ptr<float>(y);
    uchar* row = out->ptr<uchar>(y);
    int x = 0;
    for (; x + kPoints <= map.cols; x += kPoints) remapEight(source, points + 2 * x, row + x);
    if (x == map.cols) continue;
    // The last points of the row go through a group of their own, padded with (0, 0).
    float last_points[2 * kPoints] = {};
    uchar last[kPoints];
    std::copy(points + 2 * x, points + 2 * map.cols, last_points);
    remapEight(source, last_points, last);
    std::copy(last, last + (map.cols - x), row + x);
  }
}

}  // namespace movseg
