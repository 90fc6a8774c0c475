#include "cut/graph_cut.h"

#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "cut/geodesic.h"
#include "cut/max_flow.h"

namespace movseg {
namespace {

// One forward+backward raster sweep: a second one left DAVIS J (0.358 / 0.359) and the synthetic
// J unchanged and costs 0.8 ms at 320x240 (docs/design.md).
constexpr int kGeodesicSweeps = 1;

// Stands for the infinite cost of eq. (8) in the float capacities of the max-flow graph.
constexpr float kHardConstraint = 1e9f;

// Eq. (7)-(10): R_F = u G_F and R_B = u G_B, with the seeds' hard constraints.
struct Unaries {
  cv::Mat cost_fg, cost_bg;  // CV_32F
  cv::Mat confidence;        // u of eq. (10), CV_32F
};

// Distances are divided by the image width so that u(x) and therefore the balance of eq. (6)
// do not depend on the working resolution.
Unaries geodesicUnaries(const cv::Mat& d_fg, const cv::Mat& d_bg,
                        const std::vector<cv::Point>& foreground,
                        const std::vector<cv::Point>& background) {
  Unaries out{cv::Mat(d_fg.size(), CV_32F), cv::Mat(d_fg.size(), CV_32F),
              cv::Mat(d_fg.size(), CV_32F)};
  const float norm = 1.0f / static_cast<float>(d_fg.cols);
  for (int y = 0; y < d_fg.rows; ++y) {
    const float* f = d_fg.ptr<float>(y);
    const float* b = d_bg.ptr<float>(y);
    float* rf = out.cost_fg.ptr<float>(y);
    float* rb = out.cost_bg.ptr<float>(y);
    float* u = out.confidence.ptr<float>(y);
    for (int x = 0; x < d_fg.cols; ++x) {
      const float df = f[x] * norm, db = b[x] * norm, sum = df + db;
      u[x] = sum > 0.f ? (df - db) * (df - db) / sum : 0.f;  // eq. (10)
      rf[x] = sum > 0.f ? u[x] * df / sum : 0.f;              // u * G_F, eq. (9)
      rb[x] = sum > 0.f ? u[x] * db / sum : 0.f;
    }
  }
  for (const cv::Point& p : foreground) out.cost_bg.at<float>(p) = kHardConstraint;  // eq. (8)
  for (const cv::Point& p : background) out.cost_fg.at<float>(p) = kHardConstraint;
  return out;
}

// Eq. (11) for the right and the down neighbour of every pixel (0 where there is none).
// |C_i - C_j|^2 is scaled by beta = 1 / (2 <|dC|^2>), GrabCut's normalisation, so the term
// reacts to the image's own contrast whatever its bit depth or dynamic range.
struct Pairwise {
  cv::Mat right, down;  // CV_32F, already multiplied by the weight lambda of eq. (6)
};

Pairwise pairwiseWeights(const cv::Mat& colour, const cv::Mat& confidence, double weight) {
  Pairwise out{cv::Mat::zeros(colour.size(), CV_32F), cv::Mat::zeros(colour.size(), CV_32F)};
  const int w = colour.cols, h = colour.rows;
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    const auto* c = colour.ptr<cv::Vec3f>(y);
    const auto* below = colour.ptr<cv::Vec3f>(std::min(y + 1, h - 1));
    float* right = out.right.ptr<float>(y);
    float* down = out.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) sum += right[x] = static_cast<float>(cv::norm(c[x] - c[x + 1], cv::NORM_L2SQR));
      if (y + 1 < h) sum += down[x] = static_cast<float>(cv::norm(c[x] - below[x], cv::NORM_L2SQR));
    }
  }
  const long edges = static_cast<long>(w - 1) * h + static_cast<long>(h - 1) * w;
  const float beta = sum > 0 ? static_cast<float>(edges / (2 * sum)) : 0.f;
  const auto lambda = static_cast<float>(weight);
  for (int y = 0; y < h; ++y) {
    const float* u = confidence.ptr<float>(y);
    const float* u_below = confidence.ptr<float>(std::min(y + 1, h - 1));
    float* right = out.right.ptr<float>(y);
    float* down = out.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) right[x] = lambda * (1 + 0.5f * (u[x] + u[x + 1])) / (1 + beta * right[x]);
      if (y + 1 < h) down[x] = lambda * (1 + 0.5f * (u[x] + u_below[x])) / (1 + beta * down[x]);
    }
  }
  return out;
}

enum : uchar { kFree = 0, kFixedBackground = 1, kFixedForeground = 2 };

// Exact reduction: a pixel whose unary preference |R_B - R_F| exceeds the sum of its pairwise
// weights takes its preferred label in every minimum of eq. (6) (flipping it would cost more
// than any smoothness it could buy), so it needs no node in the max-flow graph.
cv::Mat decidedPixels(const Unaries& unary, const Pairwise& pairwise) {
  const int w = unary.cost_fg.cols, h = unary.cost_fg.rows;
  cv::Mat state(unary.cost_fg.size(), CV_8U);
  for (int y = 0; y < h; ++y) {
    const float* rf = unary.cost_fg.ptr<float>(y);
    const float* rb = unary.cost_bg.ptr<float>(y);
    const float* right = pairwise.right.ptr<float>(y);
    const float* down = pairwise.down.ptr<float>(y);
    const float* up = y > 0 ? pairwise.down.ptr<float>(y - 1) : nullptr;
    uchar* s = state.ptr<uchar>(y);
    for (int x = 0; x < w; ++x) {
      const float edges = right[x] + down[x] + (x > 0 ? right[x - 1] : 0.f) + (up ? up[x] : 0.f);
      const float prefer_fg = rb[x] - rf[x];
      s[x] = prefer_fg > edges ? kFixedForeground : prefer_fg < -edges ? kFixedBackground : kFree;
    }
  }
  return state;
}

// The speed-up of docs/design.md: the cut can only move the boundary of the geodesic labelling
// (D_F < D_B) so far, so pixels farther than `band` from that boundary keep the geodesic label
// and leave the graph. Not exact; measured against the full cut (band = 0) in docs/design.md.
void fixOutsideBand(const Unaries& unary, int band, cv::Mat* state) {
  const cv::Mat geodesic_fg = unary.cost_fg < unary.cost_bg;
  cv::Mat grown, shrunk, near_boundary;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * band + 1, 2 * band + 1));
  cv::dilate(geodesic_fg, grown, kernel);
  cv::erode(geodesic_fg, shrunk, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  near_boundary = grown != shrunk;
  for (int i = 0; i < state->rows * state->cols; ++i) {
    if (state->data[i] != kFree || near_boundary.data[i]) continue;
    state->data[i] = geodesic_fg.data[i] ? kFixedForeground : kFixedBackground;
  }
}

// Max-flow over the free pixels; a free pixel's edge to a decided neighbour becomes part of
// its unary cost (the cost of disagreeing with that neighbour).
FlowGraph freePixelGraph(const Unaries& unary, const Pairwise& pairwise, const cv::Mat& state,
                         cv::Mat* node) {
  const int w = state.cols, h = state.rows;
  *node = cv::Mat(state.size(), CV_32S, cv::Scalar(-1));
  FlowGraph graph;
  for (int y = 0; y < h; ++y) {
    const float* rf = unary.cost_fg.ptr<float>(y);
    const float* rb = unary.cost_bg.ptr<float>(y);
    int* n = node->ptr<int>(y);
    // Source = foreground: its capacity is the cost of the pixel being background.
    for (int x = 0; x < w; ++x) {
      if (state.at<uchar>(y, x) == kFree) n[x] = graph.addNode(rb[x], rf[x]);
    }
  }
  auto link = [&](int a, int b, float weight) {
    const int na = reinterpret_cast<const int*>(node->data)[a];
    const int nb = reinterpret_cast<const int*>(node->data)[b];
    if (na >= 0 && nb >= 0) {
      graph.addEdge(na, nb, weight);
    } else if (na >= 0 || nb >= 0) {
      const auto free_node = static_cast<size_t>(na >= 0 ? na : nb);
      const bool other_fg = state.data[na >= 0 ? b : a] == kFixedForeground;
      (other_fg ? graph.source : graph.sink)[free_node] += weight;
    }
  };
  for (int y = 0; y < h; ++y) {
    const float* right = pairwise.right.ptr<float>(y);
    const float* down = pairwise.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      const int i = y * w + x;
      if (x + 1 < w) link(i, i + 1, right[x]);
      if (y + 1 < h) link(i, i + w, down[x]);
    }
  }
  return graph;
}

cv::Mat cutFreePixels(const Unaries& unary, const Pairwise& pairwise, const cv::Mat& state,
                      MaxFlowSolver solver, int* graph_nodes) {
  cv::Mat node;
  const FlowGraph graph = freePixelGraph(unary, pairwise, state, &node);
  *graph_nodes = graph.nodes();
  const std::vector<std::uint8_t> source_side = minimumCut(graph, solver);
  cv::Mat mask(state.size(), CV_8U);
  for (int i = 0; i < state.rows * state.cols; ++i) {
    const int n = reinterpret_cast<const int*>(node.data)[i];
    mask.data[i] = n >= 0 ? (source_side[static_cast<size_t>(n)] ? 255 : 0)
                          : (state.data[i] == kFixedForeground ? 255 : 0);
  }
  return mask;
}

}  // namespace

CutResult geodesicGraphCut(const cv::Mat& bgr, const std::vector<cv::Point>& foreground,
                           const std::vector<cv::Point>& background, const Params& params,
                           MaxFlowSolver solver) {
  cv::Mat colour;
  bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
  const GeodesicGrid grid(colour, params.geodesic_gamma);
  const Unaries unary =
      geodesicUnaries(grid.distanceFrom(foreground, kGeodesicSweeps),
                      grid.distanceFrom(background, kGeodesicSweeps), foreground, background);
  const Pairwise pairwise = pairwiseWeights(colour, unary.confidence, params.cut_weight);
  cv::Mat state = decidedPixels(unary, pairwise);
  if (params.cut_band > 0) fixOutsideBand(unary, params.cut_band, &state);
  CutResult result;
  result.mask = cutFreePixels(unary, pairwise, state, solver, &result.graph_nodes);
  result.confidence = unary.confidence;
  return result;
}

}  // namespace movseg
