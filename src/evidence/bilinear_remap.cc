#include "evidence/bilinear_remap.h"

#include <algorithm>
#include <array>
#include <cstring>

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
constexpr int kMaxSide = 32767 - 2 * kBorder;  // coordinates and row step as shorts (offsets)

// The weights of eight points along one axis, from their coordinates in fixed point: 32 - f and
// f for each fraction f, two shorts per 32-bit lane (32 - f the low one); points 0-3 in `first`,
// 4-7 in `second`.
void axisWeights(const v_int32x4& fixed0, const v_int32x4& fixed1, v_int32x4* first,
                 v_int32x4* second) {
  const v_int32x4 mask = cv::v_setall_s32(kFractions - 1);
  const v_int16x8 fractions = cv::v_pack(fixed0 & mask, fixed1 & mask);
  v_int16x8 low, high;
  cv::v_zip(cv::v_setall_s16(kFractions) - fractions, fractions, low, high);
  *first = cv::v_reinterpret_as_s32(low);
  *second = cv::v_reinterpret_as_s32(high);
}

// What eight points of a map read and how they weigh it: the offsets of their 2x2 neighbourhoods
// from pixel (0, 0) in a stacked image, and their weights (axisWeights); points 0-3 in [0].
struct EightTaps {
  v_int32x4 offsets[2];
  v_int32x4 along_x[2], along_y[2];
};

// The source's shape, for the offsets: its row step in the stacked image and the bounds the
// coordinates are clamped to.
struct Geometry {
  v_int16x8 per_xy;  // (1, step) per point: the offset of (x, y) is x + y * step
  v_int16x8 max_x, max_y;
};

Geometry geometryOf(const cv::Mat& stacked, cv::Size size) {
  const auto step = static_cast<int>(stacked.step1() / 2);
  return {cv::v_reinterpret_as_s16(cv::v_setall_s32(1 + step * 65536)),
          cv::v_setall_s16(static_cast<short>(size.width)),
          cv::v_setall_s16(static_cast<short>(size.height))};
}

// Pixel (0, 0) of the image in the stacked image.
const short* originOf(const cv::Mat& stacked) {
  return reinterpret_cast<const short*>(stacked.ptr(kBorder)) + kBorder;
}

// Eight points of a map (x, y, x, y, ...).
EightTaps tapsOf(const Geometry& geometry, const float* points) {
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
  ix = cv::v_min(cv::v_max(ix, low), geometry.max_x);
  iy = cv::v_min(cv::v_max(iy, low), geometry.max_y);
  v_int16x8 xy0, xy1;
  cv::v_zip(ix, iy, xy0, xy1);
  EightTaps taps;
  taps.offsets[0] = cv::v_dotprod(xy0, geometry.per_xy);
  taps.offsets[1] = cv::v_dotprod(xy1, geometry.per_xy);
  axisWeights(fixed_x0, fixed_x1, &taps.along_x[0], &taps.along_x[1]);
  axisWeights(fixed_y0, fixed_y1, &taps.along_y[0], &taps.along_y[1]);
  return taps;
}

// Four bytes at `offset` pixels of the stacked image from `origin`: a 2x2 neighbourhood. Copied,
// as the address is only as aligned as a short (cv::v_lut_pairs reads it as an int, which
// UBSan refuses).
int neighbourhoodAt(const short* origin, int offset) {
  int bytes;
  std::memcpy(&bytes, origin + offset, sizeof bytes);
  return bytes;
}

// The 2x2 neighbourhoods at four offsets from `origin`: the bytes p00 p10 p01 p11 per point (pYX,
// Y down). The offsets leave the vector two by two, in 64-bit halves (cheaper than one by one).
v_uint8x16 neighbourhoods(const short* origin, const v_int32x4& offsets) {
  const uint64 low = cv::v_reinterpret_as_u64(offsets).get0();
  const uint64 high = cv::v_reinterpret_as_u64(cv::v_combine_high(offsets, offsets)).get0();
  return cv::v_reinterpret_as_u8(v_int32x4(
      neighbourhoodAt(origin, static_cast<int>(low)),
      neighbourhoodAt(origin, static_cast<int>(low >> 32)),
      neighbourhoodAt(origin, static_cast<int>(high)),
      neighbourhoodAt(origin, static_cast<int>(high >> 32))));
}

// Four pixels interpolated from their neighbourhoods: the columns weighed along y, then the two
// column sums along x, rounded.
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

// Eight pixels of the stacked image whose pixel (0, 0) is at `origin`, read at `taps`.
void interpolateEight(const short* origin, const EightTaps& taps, uchar* out) {
  const v_int32x4 first = interpolated(neighbourhoods(origin, taps.offsets[0]), taps.along_x[0],
                                       taps.along_y[0]);
  const v_int32x4 second = interpolated(neighbourhoods(origin, taps.offsets[1]), taps.along_x[1],
                                        taps.along_y[1]);
  cv::v_pack_u_store(out, cv::v_pack(first, second));
}

// `map` (CV_32FC2) into each of `outs` (made CV_8U of its size) from the stacked image whose pixel
// (0, 0) is at the same place in `origins`, all of the shape `geometry`: each group of points
// converted once for all of them.
template <size_t kSources>
void remapRows(const Geometry& geometry, const std::array<const short*, kSources>& origins,
               const cv::Mat& map, const std::array<cv::Mat*, kSources>& outs) {
  for (cv::Mat* out : outs) out->create(map.size(), CV_8U);
  for (int y = 0; y < map.rows; ++y) {
    const float* points = map.ptr<float>(y);
    std::array<uchar*, kSources> rows;
    for (size_t i = 0; i < kSources; ++i) rows[i] = outs[i]->template ptr<uchar>(y);
    int x = 0;
    for (; x + kPoints <= map.cols; x += kPoints) {
      const EightTaps taps = tapsOf(geometry, points + 2 * x);
      for (size_t i = 0; i < kSources; ++i) interpolateEight(origins[i], taps, rows[i] + x);
    }
    if (x == map.cols) continue;
    // The last points of the row go through a group of their own, padded with (0, 0).
    float last_points[2 * kPoints] = {};
    std::copy(points + 2 * x, points + 2 * map.cols, last_points);
    const EightTaps taps = tapsOf(geometry, last_points);
    for (size_t i = 0; i < kSources; ++i) {
      uchar last[kPoints];
      interpolateEight(origins[i], taps, last);
      std::copy(last, last + (map.cols - x), rows[i] + x);
    }
  }
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
  remapRows<1>(geometryOf(stacked_, size_), {originOf(stacked_)}, map, {out});
}

void BilinearRemap::remapBoth(const BilinearRemap& first, const BilinearRemap& second,
                              const cv::Mat& map, cv::Mat* first_out, cv::Mat* second_out) {
  CV_Assert(map.type() == CV_32FC2 && !first.stacked_.empty() && first.size_ == second.size_);
  remapRows<2>(geometryOf(first.stacked_, first.size_),
               {originOf(first.stacked_), originOf(second.stacked_)}, map, {first_out, second_out});
}

}  // namespace movseg
