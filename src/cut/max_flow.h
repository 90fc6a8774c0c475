// Minimum s-t cut of the graph of eq. (6), behind one small description so that max-flow
// implementations can be swapped and compared (BM_GraphCut in bench/pipeline_bench.cc, docs/design.md).
#pragma once

#include <cstdint>
#include <vector>

namespace movseg {

struct FlowGraph {
  // Per node: capacity from the source (cost of labelling the node sink/background) and to the
  // sink (cost of labelling it source/foreground).
  std::vector<float> source, sink;
  // Undirected pairwise edges (capacity both ways).
  std::vector<std::int32_t> edge_from, edge_to;
  std::vector<float> edge_capacity;

  int addNode(float to_source, float to_sink);
  void addEdge(int a, int b, float capacity);
  int nodes() const { return static_cast<int>(source.size()); }
};

enum class MaxFlowSolver {
  kOpenCv,  // cv::detail::GCGraph, OpenCV's Boykov–Kolmogorov (used by GrabCut)
  kBoost,   // boost::boykov_kolmogorov_max_flow (Boost.Graph)
};

// 1 where the node ends on the source side (foreground).
std::vector<std::uint8_t> minimumCut(const FlowGraph& graph, MaxFlowSolver solver);

}  // namespace movseg
