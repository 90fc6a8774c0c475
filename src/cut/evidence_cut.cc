#include "cut/evidence_cut.h"

#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "core/frame.h"
#include "cut/grid_energy.h"
#include "cut/grid_max_flow.h"

namespace movseg {
namespace {

// weight * exp(-beta d) of a squared colour step d between 8-bit colours, an integer. Looked up
// for the small steps, where most of an image's are (76 to 93 % of the edges of DAVIS frames at
// 320 pixels wide are below 2,048), so that std::exp runs once per value, not once per edge.
class ContrastWeight {
 public:
  ContrastWeight(float weight, float beta) : weight_(weight), beta_(beta) {
    for (int step = 0; step < kTabled; ++step) table_[step] = of(static_cast<float>(step));
  }

  float operator()(float step) const {
    return step < kTabled ? table_[static_cast<int>(step)] : of(step);
  }

 private:
  static constexpr int kTabled = 2048;

  float of(float step) const { return weight_ * std::exp(-beta_ * step); }

  float weight_, beta_;
  std::array<float, kTabled> table_;
};

// The size of the 2x2 blocks of an image of `size` (a last odd row or column is a block).
cv::Size blocksOf(cv::Size size) { return scaledSize(size, (size.width + 1) / 2); }

}  // namespace

void blockContrast(const cv::Mat& bgr, double smoothness, BlockContrast* contrast) {
  cv::Mat block_bgr, colour;
  cv::resize(bgr, block_bgr, blocksOf(bgr.size()), 0, 0, cv::INTER_AREA);
  block_bgr.convertTo(colour, CV_32FC3);
  // Edge weights smoothness * exp(-beta |dC|^2) to the right and down (squaredColourSteps).
  GridEnergy steps;
  const ContrastWeight weight(static_cast<float>(smoothness), squaredColourSteps(colour, &steps));
  const int w = colour.cols, h = colour.rows;
  for (int y = 0; y < h; ++y) {
    float* right = steps.right.ptr<float>(y);
    float* down = steps.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) right[x] = weight(right[x]);
      if (y + 1 < h) down[x] = weight(down[x]);
    }
  }
  contrast->right = steps.right;
  contrast->down = steps.down;
}

cv::Mat cutEvidence(const cv::Mat& evidence, const BlockContrast& contrast, GridMaxFlow* memory,
                    int* nodes) {
  CV_Assert(contrast.right.size() == blocksOf(evidence.size()));
  GridEnergy energy;
  cv::Mat block_evidence;
  cv::resize(evidence, block_evidence, contrast.right.size(), 0, 0, cv::INTER_AREA);
  energy.cost_bg = cv::max(block_evidence, 0.0);
  energy.cost_fg = cv::max(-block_evidence, 0.0);
  energy.right = contrast.right;
  energy.down = contrast.down;
  const cv::Mat labels = memory->label(energy, decidedPixels(energy), nodes);
  return upscaledMask(labels, evidence.size());
}

}  // namespace movseg
