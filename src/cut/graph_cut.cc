#include "cut/graph_cut.h"

#include "cut/geodesic.h"
#include "cut/grid_energy.h"
#include "cut/max_flow.h"

namespace movseg {
namespace {

// One forward+backward raster sweep: a second one left DAVIS J (0.358 / 0.359) and the synthetic
// J unchanged and costs 0.8 ms at 320x240 (docs/design.md).
constexpr int kGeodesicSweeps = 1;

// Stands for the infinite cost of eq. (8) in the float capacities of the max-flow graph.
constexpr float kHardConstraint = 1e9f;

// Eq. (7)-(10): R_F = u G_F and R_B = u G_B (into energy->cost_fg, cost_bg), with the seeds'
// hard constraints; returns u. Distances are divided by the image width so that u(x) and
// therefore the balance of eq. (6) do not depend on the working resolution.
cv::Mat geodesicUnaries(const cv::Mat& d_fg, const cv::Mat& d_bg,
                        const std::vector<cv::Point>& foreground,
                        const std::vector<cv::Point>& background, GridEnergy* energy) {
  cv::Mat confidence(d_fg.size(), CV_32F);
  energy->cost_fg.create(d_fg.size(), CV_32F);
  energy->cost_bg.create(d_fg.size(), CV_32F);
  const float norm = 1.0f / static_cast<float>(d_fg.cols);
  for (int y = 0; y < d_fg.rows; ++y) {
    const float* f = d_fg.ptr<float>(y);
    const float* b = d_bg.ptr<float>(y);
    float* rf = energy->cost_fg.ptr<float>(y);
    float* rb = energy->cost_bg.ptr<float>(y);
    float* u = confidence.ptr<float>(y);
    // Distances are >= 0 (0 at the seeds, sums of positive steps elsewhere), so sum is 0 only
    // where both are: dividing by 1 there gives eq. (10)'s 0 for u and both costs without a
    // branch around the divisions, which GCC then vectorises.
    for (int x = 0; x < d_fg.cols; ++x) {
      const float df = f[x] * norm, db = b[x] * norm, sum = df + db;
      const float divisor = sum > 0.f ? sum : 1.f;
      u[x] = (df - db) * (df - db) / divisor;  // eq. (10)
      rf[x] = u[x] * df / divisor;             // u * G_F, eq. (9)
      rb[x] = u[x] * db / divisor;
    }
  }
  for (const cv::Point& p : foreground) energy->cost_bg.at<float>(p) = kHardConstraint;  // eq. (8)
  for (const cv::Point& p : background) energy->cost_fg.at<float>(p) = kHardConstraint;
  return confidence;
}

// Eq. (11) for the right and the down neighbour of every pixel (0 where there is none), times
// the weight lambda of eq. (6), |C_i - C_j|^2 scaled by GrabCut's beta (squaredColourSteps).
void pairwiseWeights(const cv::Mat& colour, const cv::Mat& confidence, double weight,
                     GridEnergy* energy) {
  const float beta = squaredColourSteps(colour, energy);
  const int w = colour.cols, h = colour.rows;
  const auto lambda = static_cast<float>(weight);
  for (int y = 0; y < h; ++y) {
    const float* u = confidence.ptr<float>(y);
    const float* u_below = confidence.ptr<float>(std::min(y + 1, h - 1));
    float* right = energy->right.ptr<float>(y);
    float* down = energy->down.ptr<float>(y);
    // Two loops without a branch, which GCC vectorises.
    for (int x = 0; x + 1 < w; ++x) {
      right[x] = lambda * (1 + 0.5f * (u[x] + u[x + 1])) / (1 + beta * right[x]);
    }
    if (y + 1 == h) continue;
    for (int x = 0; x < w; ++x) {
      down[x] = lambda * (1 + 0.5f * (u[x] + u_below[x])) / (1 + beta * down[x]);
    }
  }
}

}  // namespace

CutResult geodesicGraphCut(const cv::Mat& bgr, const std::vector<cv::Point>& foreground,
                           const std::vector<cv::Point>& background, const Params& params,
                           MaxFlowSolver solver, GridMaxFlow* memory) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
  const GeodesicGrid grid(colour, params.geodesic_gamma);
  GridEnergy energy;
  CutResult result;
  result.confidence =
      geodesicUnaries(grid.distanceFrom(foreground, kGeodesicSweeps),
                      grid.distanceFrom(background, kGeodesicSweeps), foreground, background, &energy);
  pairwiseWeights(colour, result.confidence, params.cut_weight, &energy);
  cv::Mat state;
  decidedPixels(energy, &state);
  // The cut can only move the boundary of the geodesic labelling (D_F < D_B) so far
  // (docs/design.md): the pixels farther than the band keep that label. Not exact.
  if (params.cut_band > 0) fixAwayFromBoundary(energy.cost_fg < energy.cost_bg, params.cut_band, &state);
  result.mask = params.cut_refine > 0 ? labelCoarseToFine(energy, state, params.cut_refine, solver,
                                                          &result.graph_nodes, memory)
                                      : labelFreePixels(energy, state, solver,
                                                        &result.graph_nodes, memory);
  return result;
}

}  // namespace movseg
