// What the moving objects and the background look like, learnt over the stream: two colour
// histograms, updated from the pixels whose evidence is confident, forgetting at a fixed rate;
// the foreground's drawn towards the background's when few movers are seen. The same two for
// each cell of a grid (colour_cell), from its confident pixels, drawn towards the frame's: what
// a colour means where it is seen.
// Their log ratio is evidence for the pixels motion leaves undecided (a slow object's
// interior, a flat patch the flow cannot follow).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

class ColourModel {
 public:
  explicit ColourModel(const Params& params);

  // with_colour = evidence + colour_weight * clip(log(p_fg(c) / p_bg(c))) at every pixel of
  // `bgr` (8-bit BGR, evidence's size, CV_32F), the log ratio clipped to [max(-colour_clip,
  // log(1/4)), colour_clip]: a mover not seen yet may show any colour of the background;
  // evidence alone before the first update. With cells, p_fg and p_bg are the pixel's cell's.
  void addEvidence(const cv::Mat& bgr, const cv::Mat& evidence, cv::Mat* with_colour) const;

  // Learns the foreground from the pixels of `bgr` whose `evidence` (CV_32F, memory included)
  // is above colour_confidence, the background from those whose `evidence` is below
  // -colour_confidence and, each counted colour_forgetting times, from those whose
  // `pair_evidence` (the current pair's alone, before memory) is at or below it: inside the
  // carried mask, where memory lifts the evidence out of the background's reach. Otherwise a
  // static region once taken for a mover would keep itself through its colour; counted less
  // than a confident pixel, as a slow mover's still inside looks the same. The cells learn
  // from the confident pixels alone: a slow mover's still inside, most of its cells, would
  // teach them its colours as the background's.
  void update(const cv::Mat& bgr, const cv::Mat& evidence, const cv::Mat& pair_evidence);

  void reset();

 private:
  // Inline: called for the pixels rowBins() does not do sixteen at a time.
  int binOf(const cv::Vec3b& c) const {
    return bin_bits_[0][c[0]] | bin_bits_[1][c[1]] | bin_bits_[2][c[2]];
  }

  // The bins of a row of `width` pixels, into row_bins_.
  const std::uint16_t* rowBins(const cv::Vec3b* row, int width) const;

  // Counts the confident pixels of a frame into count_fg_ and count_bg_ (the background's
  // total returned) and, with kCells, each one's cell entry into cell_fg_seen_ or cell_bg_seen_.
  template <bool kCells>
  float countPixels(const cv::Mat& bgr, const cv::Mat& evidence, const cv::Mat& pair_evidence);
  // The grid of cells for frames of `size` (none where one cell would hold the frame).
  void layCells(cv::Size size);
  // Decays the cells' histograms and adds the pixels update() counted in them.
  void updateCells(float rate);
  // The colour evidence of a cell's bin (`entry`: cell * bins + bin) from the cell's histograms,
  // each drawn towards the frame's by the weight of kCellPriorPixels; stamped as worked out
  // since the last update.
  float cellEvidence(std::uint32_t entry) const;
  // The log ratio of p_fg / p_bg, clipped, times colour_weight.
  float colourSay(float foreground, float background) const;

  Params params_;
  // Per channel and 8-bit level, its bits of the bin: the first channel's are the highest.
  // Looked up rather than shifted by a shift known only at run time, which costs more.
  std::array<std::array<int, 256>, 3> bin_bits_;
  // Empty until learnt. The foreground's in pixels (a moving average of each frame's counts,
  // which fades when no mover is seen); the background's normalised.
  std::vector<float> foreground_, background_;
  std::vector<float> evidence_;              // per bin: what addEvidence() adds
  std::vector<float> count_fg_, count_bg_;  // scratch of update()
  float foreground_normaliser_ = 0;  // 1 / (the foreground's pixels + kPriorPixels)

  // The cells: a grid of cell_cols_ x cell_rows_ over frames of cells_size_ (0 x 0: none).
  cv::Size cells_size_;
  int cell_cols_ = 0, cell_rows_ = 0;
  // The column's cell and the row's first cell, as entries (cell * bins) of the tables below.
  std::vector<std::uint32_t> column_entry_, row_entry_;
  // Per cell and bin (cell * bins + bin): the histograms in pixels, moving averages as the
  // frame's foreground; per cell their sums. Each stored divided by cell_scale_.
  std::vector<float> cell_fg_, cell_bg_, cell_fg_pixels_, cell_bg_pixels_;
  float cell_scale_ = 1.f;
  // Per cell and bin: the evidence, valid where cell_stamp_ is the current update_count_ (a
  // frame shows a few hundred of a cell's bins: the others are never worked out).
  mutable std::vector<float> cell_evidence_;
  mutable std::vector<std::uint32_t> cell_stamp_;
  std::uint32_t update_count_ = 0;
  // Scratch of update(): the entry (cell * bins + bin) of each confident pixel, by side, the
  // first fg_seen_ and bg_seen_ of them this frame's.
  std::vector<std::uint32_t> cell_fg_seen_, cell_bg_seen_;
  size_t fg_seen_ = 0, bg_seen_ = 0;
  // Scratch of rowBins().
  mutable std::vector<std::uint16_t> row_bins_;
};

}  // namespace movseg
