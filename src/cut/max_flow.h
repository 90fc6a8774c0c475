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
  struct Edge {
    std::int32_t from, to;
    float capacity;
  };
  std::vector<Edge> edges;

  // Room for that many nodes and edges: a graph of a whole image would otherwise grow its
  // vectors a dozen times over.
  void reserve(int node_count, int edge_count);
  // Inline: called for every pixel of a cut.
  int addNode(float to_source, float to_sink) {
    source.push_back(to_source);
    sink.push_back(to_sink);
    return nodes() - 1;
  }
  void addEdge(int a, int b, float capacity) { edges.push_back({a, b, capacity}); }
  int nodes() const { return static_cast<int>(source.size()); }
};

enum class MaxFlowSolver {
  kOpenCv,  // cv::detail::GCGraph, OpenCV's Boykov–Kolmogorov (used by GrabCut)
  kBoost,   // boost::boykov_kolmogorov_max_flow (Boost.Graph)
  kGrid,    // the same on the pixel grid itself (cut/grid_max_flow.h): GridEnergy solves only
            // (labelFreePixels); minimumCut of a FlowGraph takes it as kOpenCv
};

// 1 where the node ends on the source side (foreground).
std::vector<std::uint8_t> minimumCut(const FlowGraph& graph, MaxFlowSolver solver);

}  // namespace movseg
