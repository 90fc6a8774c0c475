#include "cut/max_flow.h"

// Boost.Graph's templates trip GCC's -Wmaybe-uninitialized inside Boost itself (clang has no
// such warning).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#include <opencv2/core.hpp>  // gcgraph.hpp needs it first
#include <opencv2/imgproc/detail/gcgraph.hpp>

namespace movseg {

void FlowGraph::reserve(int node_count, int edge_count) {
  source.reserve(static_cast<size_t>(node_count));
  sink.reserve(static_cast<size_t>(node_count));
  edges.reserve(static_cast<size_t>(edge_count));
}

namespace {

std::vector<std::uint8_t> cutWithOpenCv(const FlowGraph& g) {
  cv::detail::GCGraph<float> graph(static_cast<unsigned>(g.nodes()),
                                   static_cast<unsigned>(2 * g.edges.size()));
  for (int i = 0; i < g.nodes(); ++i) {
    graph.addVtx();
    graph.addTermWeights(i, g.source[static_cast<size_t>(i)], g.sink[static_cast<size_t>(i)]);
  }
  for (const FlowGraph::Edge& e : g.edges) graph.addEdges(e.from, e.to, e.capacity, e.capacity);
  graph.maxFlow();
  std::vector<std::uint8_t> side(static_cast<size_t>(g.nodes()));
  for (int i = 0; i < g.nodes(); ++i) side[static_cast<size_t>(i)] = graph.inSourceSegment(i);
  return side;
}

std::vector<std::uint8_t> cutWithBoost(const FlowGraph& g) {
  using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
  using Graph = boost::adjacency_list<
      boost::vecS, boost::vecS, boost::directedS,
      boost::property<boost::vertex_index_t, long,
                      boost::property<boost::vertex_color_t, boost::default_color_type,
                                      boost::property<boost::vertex_distance_t, long,
                                                      boost::property<boost::vertex_predecessor_t,
                                                                      Traits::edge_descriptor>>>>,
      boost::property<boost::edge_capacity_t, float,
                      boost::property<boost::edge_residual_capacity_t, float,
                                      boost::property<boost::edge_reverse_t,
                                                      Traits::edge_descriptor>>>>;
  const int n = g.nodes();
  Graph graph(static_cast<size_t>(n) + 2);
  const auto source = static_cast<Traits::vertex_descriptor>(n);
  const auto sink = static_cast<Traits::vertex_descriptor>(n + 1);
  auto capacity = boost::get(boost::edge_capacity, graph);
  auto reverse = boost::get(boost::edge_reverse, graph);
  auto add = [&](Traits::vertex_descriptor a, Traits::vertex_descriptor b, float forward,
                 float backward) {
    const auto ab = boost::add_edge(a, b, graph).first;
    const auto ba = boost::add_edge(b, a, graph).first;
    capacity[ab] = forward;
    capacity[ba] = backward;
    reverse[ab] = ba;
    reverse[ba] = ab;
  };
  for (int i = 0; i < n; ++i) {
    const auto v = static_cast<Traits::vertex_descriptor>(i);
    add(source, v, g.source[static_cast<size_t>(i)], 0.f);
    add(v, sink, g.sink[static_cast<size_t>(i)], 0.f);
  }
  for (const FlowGraph::Edge& e : g.edges) {
    add(static_cast<Traits::vertex_descriptor>(e.from), static_cast<Traits::vertex_descriptor>(e.to),
        e.capacity, e.capacity);
  }
  boost::boykov_kolmogorov_max_flow(graph, source, sink);
  auto colour = boost::get(boost::vertex_color, graph);
  const auto black = boost::color_traits<boost::default_color_type>::black();
  std::vector<std::uint8_t> side(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    side[static_cast<size_t>(i)] =
        boost::get(colour, static_cast<Traits::vertex_descriptor>(i)) == black;
  }
  return side;
}

// Without edges each node is cut on its own (OpenCV's GCGraph asserts on such a graph): it
// joins the source only when that link is the stronger, as free nodes do in Boost's solver.
std::vector<std::uint8_t> cutWithoutEdges(const FlowGraph& g) {
  std::vector<std::uint8_t> side(static_cast<size_t>(g.nodes()));
  for (size_t i = 0; i < side.size(); ++i) side[i] = g.source[i] > g.sink[i];
  return side;
}

}  // namespace

std::vector<std::uint8_t> minimumCut(const FlowGraph& graph, MaxFlowSolver solver) {
  if (graph.edges.empty()) return cutWithoutEdges(graph);
  return solver == MaxFlowSolver::kBoost ? cutWithBoost(graph) : cutWithOpenCv(graph);
}

}  // namespace movseg
