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

// Edge weights smoothness * exp(-beta |dC|^2) to the right and down (squaredColourSteps) of
// 8-bit BGR.
void contrastWeights(const cv::Mat& bgr, double smoothness, GridEnergy* energy) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3);
  const ContrastWeight weight(static_cast<float>(smoothness), squaredColourSteps(colour, energy));
  const int w = bgr.cols, h = bgr.rows;
  for (int y = 0; y < h; ++y) {
    float* right = energy->right.ptr<float>(y);
    float* down = energy->down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) right[x] = weight(right[x]);
      if (y + 1 < h) down[x] = weight(down[x]);
    }
  }
}

}  // namespace

cv::Mat cutEvidence(const cv::Mat& evidence, const cv::Mat& bgr, double smoothness,
                    GridMaxFlow* memory, int* nodes) {
  const cv::Size blocks = scaledSize(bgr.size(), (bgr.cols + 1) / 2);
  GridEnergy energy;
  cv::Mat block_evidence, block_bgr;
  cv::resize(evidence, block_evidence, blocks, 0, 0, cv::INTER_AREA);
  cv::resize(bgr, block_bgr, blocks, 0, 0, cv::INTER_AREA);
  energy.cost_bg = cv::max(block_evidence, 0.0);
  energy.cost_fg = cv::max(-block_evidence, 0.0);
  contrastWeights(block_bgr, smoothness, &energy);
  const cv::Mat labels = memory->label(energy, decidedPixels(energy), nodes);
  return upscaledMask(labels, bgr.size());
}

}  // namespace movseg
