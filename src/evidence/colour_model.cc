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
// A cell's histograms are drawn towards the frame's with the weight of this many of its own
// pixels: a cell of 40 x 40 working pixels speaks for itself once it has seen a good part of
// them confidently, and a colour it has not seen means what it means in the frame. DAVIS J with
// cells of 80 x 60 px (then also learning from what the pair alone calls static): 0.607 / 0.608
// / 0.601 at 200 / 500 / 2000 (docs/design.md, "Colour where it is seen").
constexpr float kCellPriorPixels = 500.f;
// The cells' counts are stored divided by a scale that shrinks by (1 - colour_rate) a frame
// (updateCells); below this they are brought back to scale 1, every 437 frames at rate 0.1. A
// stored count stays under 1600 pixels / 1e-20, far within a float's range.
constexpr float kSmallestCellScale = 1e-20f;
// The cells' tables hold at most this many bins in all (64 MB): small cells on a large frame,
// or many colour bits, get larger cells. 40 px cells at 320 x 240 with 4 bits: 196,608.
constexpr size_t kMaxCellEntries = size_t{1} << 22;

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
  const bool cells = cell_cols_ > 0 && bgr.size() == cells_size_;
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    float* out = with_colour->ptr<float>(y);
    if (cells) {
      const std::uint32_t row_entry = row_entry_[y];
      for (int x = 0; x < bgr.cols; ++x) {
        const std::uint32_t entry = row_entry + column_entry_[x] + pixel_bins[x];
        out[x] = e[x] + (cell_stamp_[entry] == update_count_ ? cell_evidence_[entry]
                                                             : cellEvidence(entry));
      }
    } else {
      for (int x = 0; x < bgr.cols; ++x) out[x] = e[x] + evidence_[pixel_bins[x]];
    }
  }
}

void ColourModel::layCells(cv::Size size) {
  if (size == cells_size_) return;
  cells_size_ = size;
  const int bin_bits = 3 * params_.colour_bits;
  // Cells twice as wide until their tables fit kMaxCellEntries.
  for (int side = params_.colour_cell;; side *= 2) {
    cell_cols_ = side > 0 ? std::max(1, (size.width + side / 2) / side) : 0;
    cell_rows_ = side > 0 ? std::max(1, (size.height + side / 2) / side) : 0;
    if ((static_cast<size_t>(cell_cols_) * cell_rows_ << bin_bits) <= kMaxCellEntries) break;
  }
  if (cell_cols_ * cell_rows_ <= 1) cell_cols_ = cell_rows_ = 0;  // the frame's own histograms
  const int cells = cell_cols_ * cell_rows_;
  column_entry_.resize(static_cast<size_t>(size.width));
  row_entry_.resize(static_cast<size_t>(size.height));
  for (int x = 0; x < size.width; ++x) column_entry_[x] = (x * cell_cols_ / size.width) << bin_bits;
  for (int y = 0; y < size.height; ++y)
    row_entry_[y] = (y * cell_rows_ / size.height * cell_cols_) << bin_bits;
  const size_t entries = static_cast<size_t>(cells) << bin_bits;
  cell_fg_.assign(entries, 0.f);
  cell_bg_.assign(entries, 0.f);
  cell_fg_pixels_.assign(static_cast<size_t>(cells), 0.f);
  cell_bg_pixels_.assign(static_cast<size_t>(cells), 0.f);
  cell_evidence_.assign(entries, 0.f);
  cell_stamp_.assign(entries, 0);
  cell_fg_seen_.resize(static_cast<size_t>(cells > 0 ? size.area() : 0));
  cell_bg_seen_.resize(static_cast<size_t>(cells > 0 ? size.area() : 0));
}

// The cells' histograms decay by (1 - rate) a frame. Rather than every bin of every cell (a
// pass over 8 x 6 x 4096 x 2 floats at 320 x 240), the scale they are stored in shrinks, and a
// pixel counted is stored divided by it; now and then the bins are brought back to scale 1.
void ColourModel::updateCells(float rate) {
  // The first frame's counts alone (rate 1) start from zero; otherwise the scale shrinks.
  const float rescale = rate >= 1.f ? 0.f : cell_scale_ * (1.f - rate);
  if (rescale < kSmallestCellScale) {
    for (std::vector<float>* counts : {&cell_fg_, &cell_bg_, &cell_fg_pixels_, &cell_bg_pixels_})
      for (float& count : *counts) count *= rescale;
    cell_scale_ = 1.f;
  } else {
    cell_scale_ = rescale;
  }
  const float counted = rate / cell_scale_;
  const int bin_bits = 3 * params_.colour_bits;
  auto add = [&](const std::vector<std::uint32_t>& seen, size_t n, std::vector<float>* counts,
                 std::vector<float>* pixels) {
    for (size_t i = 0; i < n; ++i) {
      (*counts)[seen[i]] += counted;
      (*pixels)[seen[i] >> bin_bits] += counted;
    }
  };
  add(cell_fg_seen_, fg_seen_, &cell_fg_, &cell_fg_pixels_);
  add(cell_bg_seen_, bg_seen_, &cell_bg_, &cell_bg_pixels_);
}

float ColourModel::cellEvidence(std::uint32_t entry) const {
  const int bin_bits = 3 * params_.colour_bits;
  const std::uint32_t cell = entry >> bin_bits, bin = entry & ((1u << bin_bits) - 1);
  const float frame_fg =
      (foreground_[bin] + kPriorPixels * background_[bin]) * foreground_normaliser_;
  // A cell's share of the bin, drawn towards the frame's `share` of it.
  auto drawn = [&](float count, float pixels, float share) {
    return (count * cell_scale_ + kCellPriorPixels * share) /
           (pixels * cell_scale_ + kCellPriorPixels);
  };
  cell_evidence_[entry] =
      colourSay(drawn(cell_fg_[entry], cell_fg_pixels_[cell], frame_fg),
                drawn(cell_bg_[entry], cell_bg_pixels_[cell], background_[bin]));
  cell_stamp_[entry] = update_count_;
  return cell_evidence_[entry];
}

float ColourModel::colourSay(float foreground, float background) const {
  const auto clip = static_cast<float>(params_.colour_clip);
  const float floor = std::max(-clip, std::log(kUnseenMoverShare));
  const float ratio = std::log((foreground + kBinFloor) / (background + kBinFloor));
  return static_cast<float>(params_.colour_weight) * std::clamp(ratio, floor, clip);
}

template <bool kCells>
float ColourModel::countPixels(const cv::Mat& bgr, const cv::Mat& evidence,
                               const cv::Mat& pair_evidence) {
  const auto confident = static_cast<float>(params_.colour_confidence);
  const auto forgetting = static_cast<float>(params_.colour_forgetting);
  float* count_fg = count_fg_.data();
  float* count_bg = count_bg_.data();
  std::uint32_t* fg_seen = cell_fg_seen_.data();
  std::uint32_t* bg_seen = cell_bg_seen_.data();
  size_t fg_seen_count = 0, bg_seen_count = 0;
  float total_bg = 0;
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    const float* pair = pair_evidence.ptr<float>(y);
    const std::uint32_t row_entry = kCells ? row_entry_[y] : 0;
    for (int x = 0; x < bgr.cols; ++x) {
      if (e[x] > confident) {
        ++count_fg[pixel_bins[x]];
        if (kCells) fg_seen[fg_seen_count++] = row_entry + column_entry_[x] + pixel_bins[x];
      } else if (e[x] < -confident) {
        ++count_bg[pixel_bins[x]];
        ++total_bg;
        if (kCells) bg_seen[bg_seen_count++] = row_entry + column_entry_[x] + pixel_bins[x];
      } else if (pair[x] <= -confident) {
        count_bg[pixel_bins[x]] += forgetting;
        total_bg += forgetting;
      }
    }
  }
  fg_seen_ = fg_seen_count;
  bg_seen_ = bg_seen_count;
  return total_bg;
}

void ColourModel::update(const cv::Mat& bgr, const cv::Mat& evidence,
                         const cv::Mat& pair_evidence) {
  const size_t bins = size_t{1} << (3 * params_.colour_bits);
  count_fg_.assign(bins, 0.f);
  count_bg_.assign(bins, 0.f);
  layCells(bgr.size());
  const bool cells = cell_cols_ > 0;
  const float total_bg = cells ? countPixels<true>(bgr, evidence, pair_evidence)
                               : countPixels<false>(bgr, evidence, pair_evidence);
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
  foreground_normaliser_ = 1.f / (foreground_pixels + kPriorPixels);
  evidence_.resize(bins);
  for (size_t b = 0; b < bins; ++b) {
    const float fg = (foreground_[b] + kPriorPixels * background_[b]) * foreground_normaliser_;
    evidence_[b] = colourSay(fg, background_[b]);
  }
  if (cells) updateCells(rate);
  // Every cell's evidence is out of date; stamps start again before the count comes round.
  if (++update_count_ == 0) {
    std::fill(cell_stamp_.begin(), cell_stamp_.end(), 0);
    update_count_ = 1;
  }
}

void ColourModel::reset() {
  cells_size_ = cv::Size();  // the cells forget too: laid again by the next update
  foreground_.clear();
  background_.clear();
  evidence_.clear();
}

}  // namespace movseg
