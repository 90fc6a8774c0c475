#include "evidence/motion_evidence.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core/hal/intrin.hpp>

#include "core/quantile.h"

namespace movseg {

void LevelMap::table(uchar levels[256]) const {
  for (int v = 0; v < 256; ++v) levels[v] = cv::saturate_cast<uchar>(gain * v + offset);
}

namespace {

// A residual scale below this (pixels) is below what the flow resolves.
constexpr float kMinResidualScale = 0.1f;

}  // namespace

float residualScale(std::vector<float>* sample_residuals, const Params& params) {
  if (sample_residuals->empty()) return kMinResidualScale;
  const float upper = quantile(sample_residuals, params.evidence_quantile);
  const float median = quantile(sample_residuals, 0.5);
  return std::max({upper, static_cast<float>(params.evidence_median_factor) * median,
                   kMinResidualScale});
}

void motionEvidence(const cv::Mat& residual, float scale, const Params& params, cv::Mat* evidence) {
  const auto gain = static_cast<float>(params.evidence_gain);
  const auto offset = static_cast<float>(params.evidence_offset);
  const auto low = static_cast<float>(params.evidence_min);
  const auto high = static_cast<float>(params.evidence_max);
  evidence->create(residual.size(), CV_32F);
  for (int y = 0; y < residual.rows; ++y) {
    const float* r = residual.ptr<float>(y);
    float* e = evidence->ptr<float>(y);
    for (int x = 0; x < residual.cols; ++x) {
      e[x] = std::clamp(gain * (r[x] / scale - offset), low, high);
    }
  }
}

namespace {

using cv::v_float32x4;
using cv::v_int16x8;
using cv::v_int32x4;
using cv::v_uint16x8;

// The previous frame brought to the current one (`warped`), its absolute difference to `grey`
// (in place), averaged over the 5x5 patch the two explanations are compared over (as the texture
// measure's): the values of cv::absdiff and cv::blur.
void patchError(const cv::Mat& grey, cv::Mat* warped, BoxMean5* patch_mean, cv::Mat* error) {
  cv::absdiff(grey, *warped, *warped);
  patch_mean->apply(*warped, error);  // 8-bit: rounded, as fine as noise
}

// The median of an 8-bit image, the pixels where `ignored` (empty: none) is non-zero left out.
int median8(const cv::Mat& image, const cv::Mat& ignored) {
  LevelHistogram histogram{};
  for (int y = 0; y < image.rows; ++y) {
    const uchar* row = image.ptr<uchar>(y);
    // Unrolled: the loop's own counting and branching were half its instructions.
#pragma GCC unroll 8
    for (int x = 0; x < image.cols; ++x) ++histogram[row[x]];
    if (ignored.empty()) continue;
    const uchar* left_out = ignored.ptr<uchar>(y);
    for (int x = 0; x < image.cols; ++x) histogram[row[x]] -= left_out[x] != 0;
  }
  return median(histogram);
}

// A row of the confirmation: clamp((camera - flow) / margin, -1, 1), 16 pixels at a time. (GCC
// vectorises std::clamp into compares and blends, twice the instructions of a max and a min,
// which give the same values here: the quotient is never NaN nor -0.)
void confirmationRow(const uchar* flow, const uchar* camera, float margin, int width, float* out) {
  const v_float32x4 minus_one = cv::v_setall_f32(-1.f), one = cv::v_setall_f32(1.f);
  const v_float32x4 margins = cv::v_setall_f32(margin);
  int x = 0;
  for (; x + 16 <= width; x += 16) {
    v_uint16x8 flow_low, flow_high, camera_low, camera_high;
    cv::v_expand(cv::v_load(flow + x), flow_low, flow_high);
    cv::v_expand(cv::v_load(camera + x), camera_low, camera_high);
    const v_int16x8 better[] = {
        cv::v_reinterpret_as_s16(camera_low) - cv::v_reinterpret_as_s16(flow_low),
        cv::v_reinterpret_as_s16(camera_high) - cv::v_reinterpret_as_s16(flow_high)};
    for (int half = 0; half < 2; ++half) {
      v_int32x4 low, high;
      cv::v_expand(better[half], low, high);
      float* at = out + x + 8 * half;
      cv::v_store(at, cv::v_min(cv::v_max(cv::v_cvt_f32(low) / margins, minus_one), one));
      cv::v_store(at + 4, cv::v_min(cv::v_max(cv::v_cvt_f32(high) / margins, minus_one), one));
    }
  }
  for (; x < width; ++x) {
    out[x] = std::clamp(static_cast<float>(camera[x] - flow[x]) / margin, -1.f, 1.f);
  }
}

// fitLevels reads every fourth row: a quarter of the pixels, as many as the scene cut's, each
// row in order.
constexpr int kLevelRowStep = 4;

// The median of |grey - map(previous)| over the rows fitLevels reads.
int medianLevelError(const cv::Mat& grey, const cv::Mat& previous, const LevelMap& map) {
  uchar table[256];
  map.table(table);
  LevelHistogram histogram{};
  for (int y = 0; y < grey.rows; y += kLevelRowStep) {
    const uchar* to = grey.ptr<uchar>(y);
    const uchar* from = previous.ptr<uchar>(y);
    for (int x = 0; x < grey.cols; ++x) ++histogram[std::abs(to[x] - table[from[x]])];
  }
  return median(histogram);
}

// *image's levels through `map`, in place.
void mapLevels(const LevelMap& map, cv::Mat* image) {
  uchar table[256];
  map.table(table);
  cv::LUT(*image, cv::Mat(1, 256, CV_8U, table), *image);
}

}  // namespace

void PhotometricCheck::followFlow(const cv::Mat& previous_grey, const cv::Mat& previous_mask,
                                  const cv::Mat& flow_map, cv::Mat* carried) {
  previous_.setSource(previous_grey, cv::BORDER_REPLICATE);
  if (previous_mask.empty()) {
    carried->release();
    previous_.remap(flow_map, &by_flow_);
    return;
  }
  previous_mask_.setSource(previous_mask, cv::BORDER_CONSTANT);
  BilinearRemap::remapBoth(previous_, previous_mask_, flow_map, &by_flow_, carried);
}

LevelMap PhotometricCheck::fitLevels(const cv::Mat& grey) const {
  // Integer sums, exact (a row's in 32 bits, enough for rows under 66,000 pixels, in a loop GCC
  // vectorises); a pixel where either frame clips (0 or 255) counts 0 times.
  std::int64_t n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int y = 0; y < grey.rows; y += kLevelRowStep) {
    const uchar* to = grey.ptr<uchar>(y);
    const uchar* from = by_flow_.ptr<uchar>(y);
    std::uint32_t row_n = 0, row_x = 0, row_y = 0, row_xx = 0, row_xy = 0;
    for (int x = 0; x < grey.cols; ++x) {
      const std::uint32_t f = from[x], t = to[x];
      const std::uint32_t kept = (f != 0) & (f != 255) & (t != 0) & (t != 255);
      const std::uint32_t kf = kept * f;
      row_n += kept, row_x += kf, row_y += kept * t, row_xx += kf * f, row_xy += kf * t;
    }
    n += row_n, sx += row_x, sy += row_y, sxx += row_xx, sxy += row_xy;
  }
  // n^2 times the variance of the previous levels: at least a level's spread to fit a gain.
  const double spread = static_cast<double>(n * sxx - sx * sx);
  if (n == 0 || spread <= static_cast<double>(n) * static_cast<double>(n)) return {};
  LevelMap fitted;
  fitted.gain = static_cast<double>(n * sxy - sx * sy) / spread;
  // Light that changes by more than twice between two frames is no change of light: the fit
  // of two unrelated scenes (a cut) has a gain near their correlation, near 0.
  if (fitted.gain < 0.5 || fitted.gain > 2) return {};
  fitted.offset = (static_cast<double>(sy) - fitted.gain * static_cast<double>(sx)) /
                  static_cast<double>(n);
  const int before = medianLevelError(grey, by_flow_, LevelMap());
  const int after = medianLevelError(grey, by_flow_, fitted);
  return after < before && 2 * after <= before ? fitted : LevelMap();
}

void PhotometricCheck::confirm(const cv::Mat& grey, const cv::Mat& camera_map,
                               const LevelMap& levels, const cv::Mat& ignored,
                               const Params& params, cv::Mat* confirmation) {
  previous_.remap(camera_map, &by_camera_);
  if (!levels.identity()) {
    mapLevels(levels, &by_flow_);
    mapLevels(levels, &by_camera_);
  }
  patchError(grey, &by_flow_, &patch_mean_, &flow_error_);
  patchError(grey, &by_camera_, &patch_mean_, &camera_error_);
  // One grey level at least: an 8-bit difference cannot resolve less.
  const float margin = static_cast<float>(params.photometric_margin) *
                       static_cast<float>(std::max(median8(camera_error_, ignored), 1));
  confirmation->create(grey.size(), CV_32F);
  for (int y = 0; y < grey.rows; ++y) {
    confirmationRow(flow_error_.ptr<uchar>(y), camera_error_.ptr<uchar>(y), margin, grey.cols,
                    confirmation->ptr<float>(y));
  }
}

void confirmMotion(const cv::Mat& confirmation, const Params& params, cv::Mat* evidence) {
  // The positive part scaled, at least the floor, plus the negative part: the values of a branch
  // on the sign, in a loop GCC vectorises (a branch, or the width read through `evidence` at
  // each step, stops it).
  const auto floor = static_cast<float>(params.evidence_min);
  const int w = evidence->cols;
  for (int y = 0; y < evidence->rows; ++y) {
    const float* c = confirmation.ptr<float>(y);
    float* e = evidence->ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      e[x] = std::max(std::max(e[x], 0.f) * c[x], floor) + std::min(e[x], 0.f);
    }
  }
}

namespace {

// Whether the previous frame's mover hid what the camera puts at a pixel: the previous mask
// (CV_8U 0/255) at the nearest pixel to `at`, the pixel's place in the previous frame.
bool hiddenThere(const cv::Mat& previous_mask, const cv::Point2f& at) {
  const int x = cvRound(at.x), y = cvRound(at.y);
  return x >= 0 && y >= 0 && x < previous_mask.cols && y < previous_mask.rows &&
         previous_mask.at<uchar>(y, x) > 127;
}

// Hidden there, and the flow does not lead back into the mover (`carried` under half).
bool uncoveredAt(uchar carried, const cv::Mat& previous_mask, const cv::Point2f& at) {
  return carried <= 127 && hiddenThere(previous_mask, at);
}

}  // namespace

void uncoveredPixels(const cv::Mat& carried, const cv::Mat& previous_mask,
                     const cv::Mat& camera_map, cv::Mat* uncovered) {
  uncovered->create(carried.size(), CV_8U);
  for (int y = 0; y < carried.rows; ++y) {
    const uchar* c = carried.ptr<uchar>(y);
    const auto* at = camera_map.ptr<cv::Point2f>(y);
    uchar* out = uncovered->ptr<uchar>(y);
    for (int x = 0; x < carried.cols; ++x) {
      out[x] = uncoveredAt(c[x], previous_mask, at[x]) ? 255 : 0;
    }
  }
}

void dropUncovered(const cv::Mat& carried, const cv::Mat& previous_mask, const cv::Mat& camera_map,
                   cv::Mat* evidence) {
  const int w = evidence->cols;
  const cv::v_float32x4 zero = cv::v_setzero_f32();
  for (int y = 0; y < evidence->rows; ++y) {
    const uchar* c = carried.ptr<uchar>(y);
    const auto* at = camera_map.ptr<cv::Point2f>(y);
    float* e = evidence->ptr<float>(y);
    // Only positive evidence is dropped: the mask is looked up where there is some, four
    // pixels skipped at once where there is none (most of the background).
    const auto drop = [&](int from, int to) {
      for (int x = from; x < to; ++x) {
        if (e[x] > 0 && uncoveredAt(c[x], previous_mask, at[x])) e[x] = 0;
      }
    };
    int x = 0;
    for (; x + 4 <= w; x += 4) {
      if (cv::v_check_any(cv::v_load(e + x) > zero)) drop(x, x + 4);
    }
    drop(x, w);
  }
}

void addMemory(const cv::Mat& carried, const Params& params, const cv::Mat& evidence,
               cv::Mat* with_memory) {
  // log(p / (1 - p)) per 8-bit level of the carried mask, p softened towards one half.
  const auto floor = static_cast<float>(params.memory_floor);
  const auto weight = static_cast<float>(params.memory_weight);
  float logit[256];
  for (int level = 0; level < 256; ++level) {
    const float p = floor + (1 - 2 * floor) * static_cast<float>(level) / 255.f;
    logit[level] = weight * std::log(p / (1 - p));
  }
  with_memory->create(evidence.size(), CV_32F);
  const int w = carried.cols;
  for (int y = 0; y < carried.rows; ++y) {
    const uchar* c = carried.ptr<uchar>(y);
    const float* e = evidence.ptr<float>(y);
    float* out = with_memory->ptr<float>(y);
    const auto add = [&](int from, int to) {
      for (int x = from; x < to; ++x) out[x] = e[x] + logit[c[x]];
    };
    // Most of the carried mask is runs of one level (0 away from the mover, 255 inside it):
    // sixteen pixels of one level take one value, four floats at a time.
    int x = 0;
    for (; x + 16 <= w; x += 16) {
      if (!cv::v_check_all(cv::v_load(c + x) == cv::v_setall_u8(c[x]))) {
        add(x, x + 16);
        continue;
      }
      const cv::v_float32x4 term = cv::v_setall_f32(logit[c[x]]);
      for (int k = x; k < x + 16; k += 4) cv::v_store(out + k, cv::v_load(e + k) + term);
    }
    add(x, w);
  }
}

}  // namespace movseg
