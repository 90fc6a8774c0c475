// What the moving objects and the background look like, learnt over the stream: two colour
// histograms, updated from the pixels whose evidence is confident, forgetting at a fixed rate;
// the foreground's drawn towards the background's when few movers are seen. The same two for
// each cell of a grid (colour_cell), a bit a channel coarser, from its confident pixels, drawn
// towards the frame's: what a colour means where it is seen.
// Their log ratio is evidence for the pixels motion leaves undecided (a slow object's
// interior, a flat patch the flow cannot follow).
#pragma once

#include <algorithm>
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
  // evidence alone before the first update. With cells, p_fg and p_bg are the pixel's cell's:
  // the cell's p of the colour's coarser cell bin times the frame's p of the colour within it.
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
  // total returned) and, with kCells, into cell_count_fg_ and cell_count_bg_.
  template <bool kCells>
  float countPixels(const cv::Mat& bgr, const cv::Mat& evidence, const cv::Mat& pair_evidence);
  // The grid of cells for frames of `size` (none where one cell would hold the frame).
  void layCells(cv::Size size);
  // The first entry (cell * cell bins) of the cell at `column` of the grid and row y's cells.
  size_t cellEntry(int column, int y) const {
    return static_cast<size_t>(cell_row_[y] * cell_cols_ + column) << (3 * cell_bits_);
  }
  // Adds the pixels update() counted in the cells to their decaying histograms, then works out
  // what the cells say (setCellCorrections). `normaliser`: the frame's foreground's, as update()
  // draws it towards the background.
  void updateCells(float rate, float normaliser);
  // Every cell bin's log ratio in its cell less the frame's, into cell_correction_.
  void setCellCorrections();
  // The frame's p_fg of `bin`: the movers' counts drawn towards the background by kPriorPixels,
  // times `normaliser`, 1 / (the movers' pixels + kPriorPixels).
  float frameForeground(size_t bin, float normaliser) const;
  // log(p_fg / p_bg), kept off infinity where a bin was never seen.
  static float logRatio(float foreground, float background);
  // What colour says for a log ratio: colour_weight times it clipped to [floor, clip], the floor
  // max(-colour_clip, log(kUnseenMoverShare)).
  struct Say {
    float weight, floor, clip;
    float operator()(float ratio) const { return weight * std::clamp(ratio, floor, clip); }
  };
  Say sayOf() const;

  Params params_;
  // Per channel and 8-bit level, its bits of the bin: the first channel's are the highest.
  // Looked up rather than shifted by a shift known only at run time, which costs more.
  std::array<std::array<int, 256>, 3> bin_bits_;
  // Empty until learnt. The foreground's in pixels (a moving average of each frame's counts,
  // which fades when no mover is seen); the background's normalised.
  std::vector<float> foreground_, background_;
  std::vector<float> evidence_;             // per bin: what addEvidence() adds
  std::vector<float> ratio_;                // per bin: the log ratio, unclipped
  std::vector<float> count_fg_, count_bg_;  // scratch of update()

  // The cells: a grid of cell_cols_ x cell_rows_ over frames of cells_size_ (0 x 0: none),
  // each with histograms of cell_bits_ a channel.
  int cell_bits_;
  std::vector<std::uint16_t> cell_bin_;  // per bin: its cell bin
  // Per cell bin: the frame's p_fg and p_bg of it (sums of its bins'), and p_bg / p_fg.
  std::vector<float> cell_bin_fg_, cell_bin_bg_, frame_bg_per_fg_;
  cv::Size cells_size_;
  int cell_cols_ = 0, cell_rows_ = 0;
  // The first x of each column of cells (and the width after the last); each y's row of cells.
  std::vector<int> cell_column_start_, cell_row_;
  // Per cell and cell bin (cell * cell bins + cell bin): the histograms in pixels, moving
  // averages as the frame's foreground, the counts of update()'s frame, and what the cell says
  // beyond the frame (setCellCorrections); per cell the histograms' sums.
  std::vector<float> cell_fg_, cell_bg_, cell_count_fg_, cell_count_bg_, cell_correction_;
  std::vector<float> cell_fg_pixels_, cell_bg_pixels_;
  // Scratch of rowBins().
  mutable std::vector<std::uint16_t> row_bins_;
};

}  // namespace movseg
