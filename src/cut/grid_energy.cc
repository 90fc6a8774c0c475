#include "cut/grid_energy.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "cut/grid_max_flow.h"

namespace movseg {

void decidedPixels(const GridEnergy& energy, cv::Mat* state) {
  const int w = energy.cost_fg.cols, h = energy.cost_fg.rows;
  state->create(energy.cost_fg.size(), CV_8U);
  for (int y = 0; y < h; ++y) {
    const float* rf = energy.cost_fg.ptr<float>(y);
    const float* rb = energy.cost_bg.ptr<float>(y);
    const float* right = energy.right.ptr<float>(y);
    const float* down = energy.down.ptr<float>(y);
    const float* up = y > 0 ? energy.down.ptr<float>(y - 1) : nullptr;
    uchar* s = state->ptr<uchar>(y);
    for (int x = 0; x < w; ++x) {
      const float edges = right[x] + down[x] + (x > 0 ? right[x - 1] : 0.f) + (up ? up[x] : 0.f);
      const float prefer_fg = rb[x] - rf[x];
      s[x] = prefer_fg > edges ? kFixedForeground : prefer_fg < -edges ? kFixedBackground : kFree;
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
// (fixed pixels of one block with both labels leave it free).
cv::Mat blockState(const cv::Mat& state) {
  cv::Mat blocks((state.rows + 1) / 2, (state.cols + 1) / 2, CV_8U, cv::Scalar(255));
  for (int y = 0; y < state.rows; ++y) {
    const uchar* s = state.ptr<uchar>(y);
    uchar* b = blocks.ptr<uchar>(y / 2);
    for (int x = 0; x < state.cols; ++x) {
      uchar& block = b[x / 2];
      block = block == 255 || block == s[x] ? s[x] : static_cast<uchar>(kFree);
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
    for (int x = 0; x < w; ++x) {
      bf[x / 2] += rf[x];
      bb[x / 2] += rb[x];
      if (x % 2 == 1) b_right[x / 2] += right[x];
      if (crosses_down) b_down[x / 2] += down[x];
    }
  }
  return blocks;
}

void fixAwayFromBoundary(const cv::Mat& labels, int band, cv::Mat* state) {
  cv::Mat grown, shrunk;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {2 * band + 1, 2 * band + 1});
  cv::dilate(labels, grown, kernel);
  cv::erode(labels, shrunk, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(255));
  for (int i = 0; i < state->rows * state->cols; ++i) {
    if (state->data[i] != kFree || grown.data[i] != shrunk.data[i]) continue;
    state->data[i] = labels.data[i] ? kFixedForeground : kFixedBackground;
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
      if (x + 1 < w) sum += right[x] = static_cast<float>(cv::norm(c[x] - c[x + 1], cv::NORM_L2SQR));
      if (y + 1 < h) sum += down[x] = static_cast<float>(cv::norm(c[x] - below[x], cv::NORM_L2SQR));
    }
  }
  const long edges = static_cast<long>(w - 1) * h + static_cast<long>(h - 1) * w;
  return sum > 0 ? static_cast<float>(edges / (2 * sum)) : 0.f;
}

}  // namespace movseg
