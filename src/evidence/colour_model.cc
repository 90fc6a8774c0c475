#include "evidence/colour_model.h"

#include <algorithm>
#include <cmath>

#include <opencv2/core/hal/intrin.hpp>

namespace movseg {
namespace {

// The background's histogram says nothing until it has seen this many pixels.
constexpr float kMinPixels = 20.f;
// The foreground's colours are those of the movers seen lately and, with the weight of this
// many pixels, the background's: a mover not seen yet may look like anything in the view. So a
// few foreground pixels say little, and when no mover is seen for a while the foreground's
// histogram fades into the background's and the colour evidence to zero, instead of holding
// the last movers' colours for ever (docs/design.md, "Colour that forgets").
constexpr float kPriorPixels = 20.f;
// A mover not seen yet may show any of the background's colours: the movers' histogram, learnt
// from the movers seen so far, does not say how unlikely a colour is for the next one. So a
// colour counts against the foreground by at most this share, the foreground being at least a
// quarter as likely to show it as the background (log ratio >= log(1/4), where colour_clip
// allows -2). Against -2 (docs/design.md, "A floor under colour's say against a mover"):
// DAVIS J 0.5954 -> 0.5976, our 57 0.841 -> 0.843, independent 48 0.798 -> 0.799, dolly
// 0.123 -> 0.142; a half (log ratio >= -0.69) lost DAVIS 0.008.
constexpr float kUnseenMoverShare = 0.25f;
// Keeps a bin never seen from reading as infinitely unlikely.
constexpr float kBinFloor = 1e-4f;

}  // namespace

ColourModel::ColourModel(const Params& params) : params_(params) {
  const int bits = params.colour_bits;
  const int shift = 8 - bits;  // an 8-bit channel shifted right by this is its bin
  for (int level = 0; level < 256; ++level) {
    bin_bits_[0][level] = (level >> shift) << (2 * bits);
    bin_bits_[1][level] = (level >> shift) << bits;
    bin_bits_[2][level] = level >> shift;
  }
}

// Sixteen pixels at a time where a bin fits 16 bits (colour_bits up to 5): the channels
// shifted in 16-bit lanes, as the tables of binOf() hold them. A bin looked up per pixel cost
// twice the instructions.
const std::uint16_t* ColourModel::rowBins(const cv::Vec3b* row, int width) const {
  row_bins_.resize(static_cast<size_t>(width));
  std::uint16_t* bins = row_bins_.data();
  const int bits = params_.colour_bits, shift = 8 - bits;
  int x = 0;
  if (3 * bits <= 16) {
    for (; x + 16 <= width; x += 16) {
      cv::v_uint8x16 channel[3];
      cv::v_load_deinterleave(&row[x][0], channel[0], channel[1], channel[2]);
      cv::v_uint16x8 low = cv::v_setzero_u16(), high = low;
      for (int c = 0; c < 3; ++c) {
        cv::v_uint16x8 channel_low, channel_high;
        cv::v_expand(channel[c], channel_low, channel_high);
        const int place = (2 - c) * bits;  // the first channel's bits are the highest
        low |= (channel_low >> shift) << place;
        high |= (channel_high >> shift) << place;
      }
      cv::v_store(bins + x, low);
      cv::v_store(bins + x + 8, high);
    }
  }
  for (; x < width; ++x) bins[x] = static_cast<std::uint16_t>(binOf(row[x]));
  return bins;
}

void ColourModel::addEvidence(const cv::Mat& bgr, const cv::Mat& evidence,
                              cv::Mat* with_colour) const {
  if (evidence_.empty()) {
    evidence.copyTo(*with_colour);
    return;
  }
  with_colour->create(evidence.size(), CV_32F);
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    float* out = with_colour->ptr<float>(y);
    for (int x = 0; x < bgr.cols; ++x) out[x] = e[x] + evidence_[pixel_bins[x]];
  }
}

void ColourModel::update(const cv::Mat& bgr, const cv::Mat& evidence,
                         const cv::Mat& pair_evidence) {
  const size_t bins = size_t{1} << (3 * params_.colour_bits);
  count_fg_.assign(bins, 0.f);
  count_bg_.assign(bins, 0.f);
  float total_bg = 0;
  const auto confident = static_cast<float>(params_.colour_confidence);
  const auto forgetting = static_cast<float>(params_.colour_forgetting);
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    const float* pair = pair_evidence.ptr<float>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      if (e[x] > confident) {
        ++count_fg_[pixel_bins[x]];
      } else if (e[x] < -confident) {
        ++count_bg_[pixel_bins[x]];
        ++total_bg;
      } else if (pair[x] <= -confident) {
        count_bg_[pixel_bins[x]] += forgetting;
        total_bg += forgetting;
      }
    }
  }
  if (total_bg < kMinPixels) return;
  const bool first = background_.empty();
  const float rate = first ? 1.f : static_cast<float>(params_.colour_rate);
  foreground_.resize(bins, 0.f);
  background_.resize(bins, 0.f);
  float foreground_pixels = 0;
  for (size_t b = 0; b < bins; ++b) {
    foreground_[b] += rate * (count_fg_[b] - foreground_[b]);
    background_[b] += rate * (count_bg_[b] / total_bg - background_[b]);
    foreground_pixels += foreground_[b];
  }
  // Once per bin rather than once per pixel: at 4 bits a working frame has 14 pixels per bin.
  const auto weight = static_cast<float>(params_.colour_weight);
  const auto clip = static_cast<float>(params_.colour_clip);
  const float floor = std::max(-clip, std::log(kUnseenMoverShare));
  const float normaliser = 1.f / (foreground_pixels + kPriorPixels);
  evidence_.resize(bins);
  for (size_t b = 0; b < bins; ++b) {
    const float fg = (foreground_[b] + kPriorPixels * background_[b]) * normaliser;
    const float ratio = std::log((fg + kBinFloor) / (background_[b] + kBinFloor));
    evidence_[b] = weight * std::clamp(ratio, floor, clip);
  }
}

void ColourModel::reset() {
  foreground_.clear();
  background_.clear();
  evidence_.clear();
}

}  // namespace movseg
