// What the moving objects and the background look like, learnt over the stream: two colour
// histograms, updated from the pixels whose evidence is confident, forgetting at a fixed rate;
// the foreground's drawn towards the background's when few movers are seen.
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
  // evidence alone before the first update.
  void addEvidence(const cv::Mat& bgr, const cv::Mat& evidence, cv::Mat* with_colour) const;

  // Learns the foreground from the pixels of `bgr` whose `evidence` (CV_32F, memory included)
  // is above colour_confidence, the background from those whose `evidence` is below
  // -colour_confidence and, each counted colour_forgetting times, from those whose
  // `pair_evidence` (the current pair's alone, before memory) is at or below it: inside the
  // carried mask, where memory lifts the evidence out of the background's reach. Otherwise a
  // static region once taken for a mover would keep itself through its colour; counted less
  // than a confident pixel, as a slow mover's still inside looks the same.
  void update(const cv::Mat& bgr, const cv::Mat& evidence, const cv::Mat& pair_evidence);

  void reset();

 private:
  // Inline: called for the pixels rowBins() does not do sixteen at a time.
  int binOf(const cv::Vec3b& c) const {
    return bin_bits_[0][c[0]] | bin_bits_[1][c[1]] | bin_bits_[2][c[2]];
  }

  // The bins of a row of `width` pixels, into row_bins_.
  const std::uint16_t* rowBins(const cv::Vec3b* row, int width) const;

  Params params_;
  // Per channel and 8-bit level, its bits of the bin: the first channel's are the highest.
  // Looked up rather than shifted by a shift known only at run time, which costs more.
  std::array<std::array<int, 256>, 3> bin_bits_;
  // Empty until learnt. The foreground's in pixels (a moving average of each frame's counts,
  // which fades when no mover is seen); the background's normalised.
  std::vector<float> foreground_, background_;
  std::vector<float> evidence_;              // per bin: what addEvidence() adds
  std::vector<float> count_fg_, count_bg_;  // scratch of update()
  // Scratch of rowBins().
  mutable std::vector<std::uint16_t> row_bins_;
};

}  // namespace movseg
