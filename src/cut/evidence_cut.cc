#include "cut/evidence_cut.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "core/frame.h"
#include "cut/grid_energy.h"

namespace movseg {
namespace {

// Edge weights smoothness * exp(-beta |dC|^2) to the right and down (squaredColourSteps).
void contrastWeights(const cv::Mat& bgr, double smoothness, GridEnergy* energy) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3);
  const float beta = squaredColourSteps(colour, energy);
  const int w = bgr.cols, h = bgr.rows;
  const auto weight = static_cast<float>(smoothness);
  for (int y = 0; y < h; ++y) {
    float* right = energy->right.ptr<float>(y);
    float* down = energy->down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) right[x] = weight * std::exp(-beta * right[x]);
      if (y + 1 < h) down[x] = weight * std::exp(-beta * down[x]);
    }
  }
}

}  // namespace

cv::Mat cutEvidence(const cv::Mat& evidence, const cv::Mat& bgr, double smoothness, int* nodes) {
  const cv::Size blocks = scaledSize(bgr.size(), (bgr.cols + 1) / 2);
  GridEnergy energy;
  cv::Mat block_evidence, block_bgr;
  cv::resize(evidence, block_evidence, blocks, 0, 0, cv::INTER_AREA);
  cv::resize(bgr, block_bgr, blocks, 0, 0, cv::INTER_AREA);
  energy.cost_bg = cv::max(block_evidence, 0.0);
  energy.cost_fg = cv::max(-block_evidence, 0.0);
  contrastWeights(block_bgr, smoothness, &energy);
  const cv::Mat labels =
      labelFreePixels(energy, decidedPixels(energy), MaxFlowSolver::kOpenCv, nodes);
  return upscaledMask(labels, bgr.size());
}

}  // namespace movseg
