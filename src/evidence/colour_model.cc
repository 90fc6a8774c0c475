#include "evidence/colour_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>

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
// A cell's bins have one bit a channel fewer than the frame's (but one at least): 512 at 4 bits,
// for the ~1600 pixels of a 40 x 40 cell, where the frame's 4096 have ~19 pixels each at 320 x
// 240. Within a cell's bin the frame's finer histograms tell colours apart (setCellCorrections).
constexpr int kCellCoarserBits = 1;
// The cells' tables hold at most this many bins in all (1 MB each): small cells on a large
// frame, or many colour bits, get larger cells; every bin is decayed each frame. 40 px cells
// at 320 x 240 with 4 bits: 24,576.
constexpr size_t kMaxCellEntries = size_t{1} << 18;
// A decaying count or share below this is zero: a bin not seen for ~850 frames would otherwise
// sink to a subnormal float and stay there (x + 0.1 (0 - x) rounds back to x), and arithmetic on
// subnormals is many times slower on some CPUs. Far below anything that changes a sum with
// kBinFloor or a cell's prior.
constexpr float kNegligible = 1e-30f;

// `value` moved by `rate` towards `target`, a moving average; zero once negligible.
float decayed(float value, float target, float rate) {
  const float moved = value + rate * (target - value);
  return moved < kNegligible ? 0.f : moved;
}

}  // namespace

ColourModel::ColourModel(const Params& params)
    : params_(params), cell_bits_(std::max(1, params.colour_bits - kCellCoarserBits)) {
  const int bits = params.colour_bits;
  const int shift = 8 - bits;  // an 8-bit channel shifted right by this is its bin
  for (int level = 0; level < 256; ++level) {
    bin_bits_[0][level] = (level >> shift) << (2 * bits);
    bin_bits_[1][level] = (level >> shift) << bits;
    bin_bits_[2][level] = level >> shift;
  }
  // A bin's cell bin: each channel's level with its lowest bits dropped.
  const int dropped = bits - cell_bits_, mask = (1 << bits) - 1;
  cell_bin_.resize(size_t{1} << (3 * bits));
  for (size_t bin = 0; bin < cell_bin_.size(); ++bin) {
    int cell_bin = 0;
    for (int c = 0; c < 3; ++c) {
      const int level = static_cast<int>(bin >> ((2 - c) * bits)) & mask;
      cell_bin |= (level >> dropped) << ((2 - c) * cell_bits_);
    }
    cell_bin_[bin] = static_cast<std::uint16_t>(cell_bin);
  }
}

// Sixteen pixels at a time, the channels shifted in 16-bit lanes (a bin fits 16 bits:
// colour_bits is at most 5), as the tables of binOf() hold them. A bin looked up per pixel cost
// twice the instructions.
const std::uint16_t* ColourModel::rowBins(const cv::Vec3b* row, int width) const {
  row_bins_.resize(static_cast<size_t>(width));
  std::uint16_t* bins = row_bins_.data();
  const int bits = params_.colour_bits, shift = 8 - bits;
  int x = 0;
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
  const Say say = sayOf();
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    float* out = with_colour->ptr<float>(y);
    if (!cells) {
      for (int x = 0; x < bgr.cols; ++x) out[x] = e[x] + evidence_[pixel_bins[x]];
      continue;
    }
    for (int column = 0; column < cell_cols_; ++column) {
      const float* correction = cell_correction_.data() + cellEntry(column, y);
      for (int x = cell_column_start_[column]; x < cell_column_start_[column + 1]; ++x) {
        const float ratio = ratio_[pixel_bins[x]] + correction[cell_bin_[pixel_bins[x]]];
        out[x] = e[x] + say(ratio);
      }
    }
  }
}

void ColourModel::layCells(cv::Size size) {
  if (size == cells_size_) return;
  cells_size_ = size;
  const int bin_bits = 3 * cell_bits_;
  // Cells twice as wide until their tables fit kMaxCellEntries.
  for (int side = params_.colour_cell;; side *= 2) {
    cell_cols_ = side > 0 ? std::max(1, (size.width + side / 2) / side) : 0;
    cell_rows_ = side > 0 ? std::max(1, (size.height + side / 2) / side) : 0;
    if ((static_cast<size_t>(cell_cols_) * cell_rows_ << bin_bits) <= kMaxCellEntries) break;
  }
  if (cell_cols_ * cell_rows_ <= 1) cell_cols_ = cell_rows_ = 0;  // the frame's own histograms
  const int cells = cell_cols_ * cell_rows_;
  cell_column_start_.resize(static_cast<size_t>(cell_cols_) + 1);
  // Each column's first x: the least with x * cols / width >= column.
  const int columns = std::max(1, cell_cols_);
  for (int column = 0; column <= cell_cols_; ++column)
    cell_column_start_[column] =
        static_cast<int>((std::int64_t{column} * size.width + columns - 1) / columns);
  cell_row_.resize(static_cast<size_t>(size.height));
  for (int y = 0; y < size.height; ++y) cell_row_[y] = y * cell_rows_ / size.height;
  const size_t entries = static_cast<size_t>(cells) << bin_bits;
  for (std::vector<float>* table :
       {&cell_fg_, &cell_bg_, &cell_count_fg_, &cell_count_bg_, &cell_correction_})
    table->assign(entries, 0.f);
  cell_fg_pixels_.assign(static_cast<size_t>(cells), 0.f);
  cell_bg_pixels_.assign(static_cast<size_t>(cells), 0.f);
}

// Moving averages of the cells' counts, as the frame's foreground, and what they say.
void ColourModel::updateCells(float rate, float normaliser) {
  const size_t cell_bins = size_t{1} << (3 * cell_bits_);
  // The frame's p_fg and p_bg of each cell bin, sums of its bins'.
  cell_bin_fg_.assign(cell_bins, 0.f);
  cell_bin_bg_.assign(cell_bins, 0.f);
  for (size_t b = 0; b < foreground_.size(); ++b) {
    cell_bin_fg_[cell_bin_[b]] += frameForeground(b, normaliser);
    cell_bin_bg_[cell_bin_[b]] += background_[b];
  }
  frame_bg_per_fg_.resize(cell_bins);
  for (size_t bin = 0; bin < cell_bins; ++bin)
    frame_bg_per_fg_[bin] = (cell_bin_bg_[bin] + kBinFloor) / (cell_bin_fg_[bin] + kBinFloor);
  auto learn = [&](std::vector<float>* counts, const std::vector<float>& counted,
                   std::vector<float>* pixels) {
    for (size_t entry = 0; entry < counts->size(); ++entry)
      (*counts)[entry] = decayed((*counts)[entry], counted[entry], rate);
    for (size_t cell = 0; cell < pixels->size(); ++cell) {
      const auto first = counts->begin() + static_cast<std::ptrdiff_t>(cell * cell_bins);
      (*pixels)[cell] = std::accumulate(first, first + static_cast<std::ptrdiff_t>(cell_bins), 0.f);
    }
  };
  learn(&cell_fg_, cell_count_fg_, &cell_fg_pixels_);
  learn(&cell_bg_, cell_count_bg_, &cell_bg_pixels_);
  setCellCorrections();
}

// A cell knows its colours coarsely, the frame finely: p(colour) in a cell is the cell's p of
// the colour's cell bin, drawn towards the frame's by the weight of kCellPriorPixels, times the
// frame's p of the colour within that bin. So the cell's log ratio is the frame's plus a
// correction per cell bin: the cell's log ratio of the bin less the frame's. A cell that has
// seen nothing adds nothing. Every bin of every cell, its ratio first and then the logs in one
// vectorised pass: a frame shows most cells' common bins, and a bin worked out when first
// looked up cost more in addEvidence() than this.
void ColourModel::setCellCorrections() {
  const size_t cell_bins = size_t{1} << (3 * cell_bits_);
  for (size_t cell = 0; cell < cell_fg_pixels_.size(); ++cell) {
    const float fg_scale = 1.f / (cell_fg_pixels_[cell] + kCellPriorPixels);
    const float bg_scale = 1.f / (cell_bg_pixels_[cell] + kCellPriorPixels);
    const size_t first = cell * cell_bins;
    for (size_t bin = 0; bin < cell_bins; ++bin) {
      const float fg = (cell_fg_[first + bin] + kCellPriorPixels * cell_bin_fg_[bin]) * fg_scale;
      const float bg = (cell_bg_[first + bin] + kCellPriorPixels * cell_bin_bg_[bin]) * bg_scale;
      cell_correction_[first + bin] = (fg + kBinFloor) / (bg + kBinFloor) * frame_bg_per_fg_[bin];
    }
  }
  cv::Mat corrections(1, static_cast<int>(cell_correction_.size()), CV_32F,
                      cell_correction_.data());
  cv::log(corrections, corrections);
}

float ColourModel::frameForeground(size_t bin, float normaliser) const {
  return (foreground_[bin] + kPriorPixels * background_[bin]) * normaliser;
}

float ColourModel::logRatio(float foreground, float background) {
  return std::log((foreground + kBinFloor) / (background + kBinFloor));
}

ColourModel::Say ColourModel::sayOf() const {
  const auto clip = static_cast<float>(params_.colour_clip);
  return {static_cast<float>(params_.colour_weight), std::max(-clip, std::log(kUnseenMoverShare)),
          clip};
}

template <bool kCells>
float ColourModel::countPixels(const cv::Mat& bgr, const cv::Mat& evidence,
                               const cv::Mat& pair_evidence) {
  const auto confident = static_cast<float>(params_.colour_confidence);
  const auto forgetting = static_cast<float>(params_.colour_forgetting);
  float* count_fg = count_fg_.data();
  float* count_bg = count_bg_.data();
  float total_bg = 0;
  const int columns = kCells ? cell_cols_ : 1;
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint16_t* pixel_bins = rowBins(bgr.ptr<cv::Vec3b>(y), bgr.cols);
    const float* e = evidence.ptr<float>(y);
    const float* pair = pair_evidence.ptr<float>(y);
    for (int column = 0; column < columns; ++column) {
      float* cell_fg = kCells ? cell_count_fg_.data() + cellEntry(column, y) : nullptr;
      float* cell_bg = kCells ? cell_count_bg_.data() + cellEntry(column, y) : nullptr;
      const int end = kCells ? cell_column_start_[column + 1] : bgr.cols;
      for (int x = kCells ? cell_column_start_[column] : 0; x < end; ++x) {
        if (e[x] > confident) {
          ++count_fg[pixel_bins[x]];
          if (kCells) ++cell_fg[cell_bin_[pixel_bins[x]]];
        } else if (e[x] < -confident) {
          ++count_bg[pixel_bins[x]];
          ++total_bg;
          if (kCells) ++cell_bg[cell_bin_[pixel_bins[x]]];
        } else if (pair[x] <= -confident) {
          count_bg[pixel_bins[x]] += forgetting;
          total_bg += forgetting;
        }
      }
    }
  }
  return total_bg;
}

void ColourModel::update(const cv::Mat& bgr, const cv::Mat& evidence,
                         const cv::Mat& pair_evidence) {
  const size_t bins = size_t{1} << (3 * params_.colour_bits);
  count_fg_.assign(bins, 0.f);
  count_bg_.assign(bins, 0.f);
  layCells(bgr.size());
  const bool cells = cell_cols_ > 0;
  if (cells) {
    std::fill(cell_count_fg_.begin(), cell_count_fg_.end(), 0.f);
    std::fill(cell_count_bg_.begin(), cell_count_bg_.end(), 0.f);
  }
  const float total_bg = cells ? countPixels<true>(bgr, evidence, pair_evidence)
                               : countPixels<false>(bgr, evidence, pair_evidence);
  if (total_bg < kMinPixels) return;
  const bool first = background_.empty();
  const float rate = first ? 1.f : static_cast<float>(params_.colour_rate);
  foreground_.resize(bins, 0.f);
  background_.resize(bins, 0.f);
  float foreground_pixels = 0;
  for (size_t b = 0; b < bins; ++b) {
    foreground_[b] = decayed(foreground_[b], count_fg_[b], rate);
    background_[b] = decayed(background_[b], count_bg_[b] / total_bg, rate);
    foreground_pixels += foreground_[b];
  }
  const float normaliser = 1.f / (foreground_pixels + kPriorPixels);
  const Say say = sayOf();
  evidence_.resize(bins);
  ratio_.resize(bins);
  for (size_t b = 0; b < bins; ++b) {
    ratio_[b] = logRatio(frameForeground(b, normaliser), background_[b]);
    evidence_[b] = say(ratio_[b]);
  }
  if (cells) updateCells(rate, normaliser);
}

void ColourModel::reset() {
  cells_size_ = cv::Size();  // the cells forget too: laid again by the next update
  foreground_.clear();
  background_.clear();
  evidence_.clear();
}

}  // namespace movseg
