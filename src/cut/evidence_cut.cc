#include "cut/evidence_cut.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "core/frame.h"
#include "cut/grid_energy.h"

namespace movseg {
namespace {

// Edge weights smoothness * exp(-beta |dC|^2) to the right and down, beta = 1 / (2 <|dC|^2>)
// over the image (GrabCut's normalisation: the term reacts to the image's own contrast).
void contrastWeights(const cv::Mat& bgr, double smoothness, GridEnergy* energy) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3);
  energy->right = cv::Mat::zeros(bgr.size(), CV_32F);
  energy->down = cv::Mat::zeros(bgr.size(), CV_32F);
  const int w = bgr.cols, h = bgr.rows;
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    const auto* c = colour.ptr<cv::Vec3f>(y);
    const auto* below = colour.ptr<cv::Vec3f>(std::min(y + 1, h - 1));
    float* right = energy->right.ptr<float>(y);
    float* down = energy->down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) {
        const cv::Vec3f d = c[x] - c[x + 1];
        sum += right[x] = d.dot(d);
      }
      if (y + 1 < h) {
        const cv::Vec3f d = c[x] - below[x];
        sum += down[x] = d.dot(d);
      }
    }
  }
  const double edges = static_cast<double>(w - 1) * h + static_cast<double>(h - 1) * w;
  const auto beta = static_cast<float>(sum > 0 ? edges / (2 * sum) : 0.0);
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
