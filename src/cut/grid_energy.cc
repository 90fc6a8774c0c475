#include "cut/grid_energy.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "cut/grid_max_flow.h"

namespace movseg {

namespace {

// One row of decidedPixels(); `up` is the row above's down weights, none on the first row. The
// first row and column have no edge above or to the left: weight 0, added as such so the sums
// stay those of the formula. With them out of the loop and the state made by arithmetic on the
// two comparisons (not by branches), GCC vectorises it.
template <bool kHasUp>
void decideRow(const GridEnergy& energy, int y, uchar* s) {
  const float* rf = energy.cost_fg.ptr<float>(y);
  const float* rb = energy.cost_bg.ptr<float>(y);
  const float* right = energy.right.ptr<float>(y);
  const float* down = energy.down.ptr<float>(y);
  const float* up = kHasUp ? energy.down.ptr<float>(y - 1) : nullptr;
  auto decide = [&](int x, float left) {
    const float edges = right[x] + down[x] + left + (kHasUp ? up[x] : 0.f);
    const float prefer_fg = rb[x] - rf[x];
    const bool fg = prefer_fg > edges, bg = prefer_fg < -edges;  // fg wins if both (edges < 0)
    s[x] = static_cast<uchar>(fg * kFixedForeground + (!fg & bg) * kFixedBackground);
  };
  const int w = energy.cost_fg.cols;
  if (w > 0) decide(0, 0.f);
  for (int x = 1; x < w; ++x) decide(x, right[x - 1]);
}

}  // namespace

void decidedPixels(const GridEnergy& energy, cv::Mat* state) {
  state->create(energy.cost_fg.size(), CV_8U);
  for (int y = 0; y < state->rows; ++y) {
    if (y == 0) {
      decideRow<false>(energy, y, state->ptr<uchar>(y));
    } else {
      decideRow<true>(energy, y, state->ptr<uchar>(y));
    }
  }
}

namespace {

// The max-flow graph of the free pixels; node(y, x) is the pixel's node, -1 when fixed.
FlowGraph freePixelGraph(const GridEnergy& energy, const cv::Mat& state, cv::Mat* node) {
  const int w = state.cols, h = state.rows;
  *node = cv::Mat(state.size(), CV_32S, cv::Scalar(-1));
  FlowGraph graph;
  graph.reserve(w * h, (w - 1) * h + (h - 1) * w);  // as if every pixel were free
  for (int y = 0; y < h; ++y) {
    const float* rf = energy.cost_fg.ptr<float>(y);
    const float* rb = energy.cost_bg.ptr<float>(y);
    const uchar* s = state.ptr<uchar>(y);
    int* n = node->ptr<int>(y);
    // Source = foreground: its capacity is the cost of the pixel being background.
    for (int x = 0; x < w; ++x) {
      if (s[x] == kFree) n[x] = graph.addNode(rb[x], rf[x]);
    }
  }
  const auto* nodes = reinterpret_cast<const int*>(node->data);
  auto link = [&](int a, int b, float weight) {
    const int na = nodes[a], nb = nodes[b];
    if (na >= 0 && nb >= 0) {
      graph.addEdge(na, nb, weight);
    } else if (na >= 0 || nb >= 0) {
      const auto free_node = static_cast<size_t>(na >= 0 ? na : nb);
      const bool other_fg = state.data[na >= 0 ? b : a] == kFixedForeground;
      (other_fg ? graph.source : graph.sink)[free_node] += weight;
    }
  };
  for (int y = 0; y < h; ++y) {
    const float* right = energy.right.ptr<float>(y);
    const float* down = energy.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      const int i = y * w + x;
      if (x + 1 < w) link(i, i + 1, right[x]);
      if (y + 1 < h) link(i, i + w, down[x]);
    }
  }
  return graph;
}

// The block state: free when any of its pixels is free, else the label its pixels agree on
// (fixed pixels of one block with both labels leave it free): the pixels' state when all four
// agree, else kFree. A last odd row or column counts its pixels twice.
cv::Mat blockState(const cv::Mat& state) {
  cv::Mat blocks((state.rows + 1) / 2, (state.cols + 1) / 2, CV_8U);
  const int last_x = state.cols - 1;
  for (int by = 0; by < blocks.rows; ++by) {
    const uchar* top = state.ptr<uchar>(2 * by);
    const uchar* bottom = state.ptr<uchar>(std::min(2 * by + 1, state.rows - 1));
    uchar* b = blocks.ptr<uchar>(by);
    for (int bx = 0; bx < blocks.cols; ++bx) {
      const int x0 = 2 * bx, x1 = std::min(x0 + 1, last_x);
      const uchar v = top[x0];
      const bool agree = (top[x1] == v) & (bottom[x0] == v) & (bottom[x1] == v);
      b[bx] = agree ? v : static_cast<uchar>(kFree);
    }
  }
  return blocks;
}

}  // namespace

cv::Mat labelFreePixels(const GridEnergy& energy, const cv::Mat& state, MaxFlowSolver solver,
                        int* nodes, GridMaxFlow* memory) {
  if (solver == MaxFlowSolver::kGrid) {
    cv::Mat labels;
    if (memory) {
      memory->label(energy, state, nodes, &labels);
    } else {
      GridMaxFlow().label(energy, state, nodes, &labels);
    }
    return labels;
  }
  cv::Mat node;
  const FlowGraph graph = freePixelGraph(energy, state, &node);
  *nodes = graph.nodes();
  const std::vector<std::uint8_t> source_side = minimumCut(graph, solver);
  cv::Mat labels(state.size(), CV_8U);
  const auto* n = reinterpret_cast<const int*>(node.data);
  for (int i = 0; i < state.rows * state.cols; ++i) {
    labels.data[i] = n[i] >= 0 ? (source_side[static_cast<size_t>(n[i])] ? 255 : 0)
                               : (state.data[i] == kFixedForeground ? 255 : 0);
  }
  return labels;
}

GridEnergy coarsened(const GridEnergy& energy) {
  const cv::Size size((energy.cost_fg.cols + 1) / 2, (energy.cost_fg.rows + 1) / 2);
  GridEnergy blocks{cv::Mat::zeros(size, CV_32F), cv::Mat::zeros(size, CV_32F),
                    cv::Mat::zeros(size, CV_32F), cv::Mat::zeros(size, CV_32F)};
  const int w = energy.cost_fg.cols, h = energy.cost_fg.rows;
  for (int y = 0; y < h; ++y) {
    const float* rf = energy.cost_fg.ptr<float>(y);
    const float* rb = energy.cost_bg.ptr<float>(y);
    const float* right = energy.right.ptr<float>(y);
    const float* down = energy.down.ptr<float>(y);
    float* bf = blocks.cost_fg.ptr<float>(y / 2);
    float* bb = blocks.cost_bg.ptr<float>(y / 2);
    float* b_right = blocks.right.ptr<float>(y / 2);
    float* b_down = blocks.down.ptr<float>(y / 2);
    const bool crosses_down = y % 2 == 1;  // the edge below row y leaves the block
    // A block's two pixels of the row, left then right: the sums add in raster order.
    for (int x = 0; x + 1 < w; x += 2) {
      bf[x / 2] = bf[x / 2] + rf[x] + rf[x + 1];
      bb[x / 2] = bb[x / 2] + rb[x] + rb[x + 1];
      b_right[x / 2] += right[x + 1];  // the edge right of an odd pixel leaves the block
      if (crosses_down) b_down[x / 2] = b_down[x / 2] + down[x] + down[x + 1];
    }
    if (w % 2 == 1) {  // a last block one pixel wide
      bf[w / 2] += rf[w - 1];
      bb[w / 2] += rb[w - 1];
      if (crosses_down) b_down[w / 2] += down[w - 1];
    }
  }
  return blocks;
}

void fixAwayFromBoundary(const cv::Mat& labels, int band, cv::Mat* state) {
  cv::Mat grown, shrunk;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {2 * band + 1, 2 * band + 1});
  cv::dilate(labels, grown, kernel);
  cv::erode(labels, shrunk, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  // Selects and a bitwise and rather than branches, and the bound and pointers in locals (a
  // byte store could change them otherwise), so that GCC vectorises the loop.
  uchar* s = state->data;
  const uchar *grown_at = grown.data, *shrunk_at = shrunk.data, *label = labels.data;
  const int n = state->rows * state->cols;
  for (int i = 0; i < n; ++i) {
    const bool fix = (s[i] == kFree) & (grown_at[i] == shrunk_at[i]);
    const uchar fixed = label[i] ? kFixedForeground : kFixedBackground;
    s[i] = fix ? fixed : s[i];
  }
}

cv::Mat labelCoarseToFine(const GridEnergy& energy, const cv::Mat& state, int refine,
                          MaxFlowSolver solver, int* nodes, GridMaxFlow* memory) {
  int coarse_nodes = 0, fine_nodes = 0;
  const cv::Mat blocks =
      labelFreePixels(coarsened(energy), blockState(state), solver, &coarse_nodes, memory);
  cv::Mat labels;
  cv::resize(blocks, labels, state.size(), 0, 0, cv::INTER_NEAREST);
  cv::Mat fine_state = state.clone();
  fixAwayFromBoundary(labels, refine, &fine_state);
  labels = labelFreePixels(energy, fine_state, solver, &fine_nodes, memory);
  *nodes = coarse_nodes + fine_nodes;
  return labels;
}

namespace {

// cv::norm(a - b, NORM_L2SQR) of two Vec3f, as OpenCV sums it (in float, channel by channel),
// without its call.
float squaredStep(const cv::Vec3f& a, const cv::Vec3f& b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

}  // namespace

float squaredColourSteps(const cv::Mat& colour, GridEnergy* energy) {
  for (cv::Mat* steps : {&energy->right, &energy->down}) {
    steps->create(colour.size(), CV_32F);
    *steps = cv::Scalar::all(0);  // a memset, where setTo(0) allocates a copy of the scalar
  }
  const int w = colour.cols, h = colour.rows;
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    const auto* c = colour.ptr<cv::Vec3f>(y);
    const auto* below = colour.ptr<cv::Vec3f>(std::min(y + 1, h - 1));
    float* right = energy->right.ptr<float>(y);
    float* down = energy->down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) sum += right[x] = squaredStep(c[x], c[x + 1]);
      if (y + 1 < h) sum += down[x] = squaredStep(c[x], below[x]);
    }
  }
  const long edges = static_cast<long>(w - 1) * h + static_cast<long>(h - 1) * w;
  return sum > 0 ? static_cast<float>(edges / (2 * sum)) : 0.f;
}

}  // namespace movseg
