// §3.3 geodesic graph cut and the max-flow backends.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "cut/graph_cut.h"
#include "cut/max_flow.h"
#include "test_support.h"

namespace movseg {
namespace {

TEST(GraphCut, SeparatesTwoFlatColourRegionsExactly) {
  cv::Mat bgr(60, 80, CV_8UC3, cv::Scalar(200, 60, 30));
  cv::Mat truth = cv::Mat::zeros(bgr.size(), CV_8U);
  cv::circle(bgr, {45, 30}, 18, cv::Scalar(30, 160, 220), cv::FILLED);
  cv::circle(truth, {45, 30}, 18, 255, cv::FILLED);
  // Sparse seeds, far from the boundary, as features would be.
  const std::vector<cv::Point> fg{{45, 30}, {40, 25}}, bg{{5, 5}, {75, 55}, {5, 55}};
  for (int band : {0, 8}) {
    for (int refine : {0, 3}) {
      Params params;
      params.cut_band = band;
      params.cut_refine = refine;
      const CutResult cut = geodesicGraphCut(bgr, fg, bg, params);
      EXPECT_EQ(cv::countNonZero(cut.mask != truth), 0) << "band " << band << ", refine " << refine;
    }
  }
}

TEST(GraphCut, HardConstraintsHoldAtTheSeeds) {
  const cv::Mat bgr = test::texture({64, 48}, 2);
  const std::vector<cv::Point> fg{{10, 10}, {50, 40}}, bg{{11, 10}, {30, 20}};
  const CutResult cut = geodesicGraphCut(bgr, fg, bg, Params());
  for (const cv::Point& p : fg) EXPECT_EQ(cut.mask.at<uchar>(p), 255);
  for (const cv::Point& p : bg) EXPECT_EQ(cut.mask.at<uchar>(p), 0);
}

TEST(GraphCut, ConfidenceIsLowWhereBothSeedSetsAreEquallyFar) {
  cv::Mat bgr(20, 41, CV_8UC3, cv::Scalar(90, 90, 90));
  const CutResult cut = geodesicGraphCut(bgr, {{0, 10}}, {{40, 10}}, Params());
  EXPECT_NEAR(cut.confidence.at<float>(10, 20), 0.f, 1e-6);
  EXPECT_GT(cut.confidence.at<float>(10, 2), 0.5f);
}

// Both backends must find a minimum cut of the same energy; on random graphs with distinct
// capacities the minimum is unique, so the labels agree.
TEST(MaxFlow, OpenCvAndBoostAgree) {
  cv::RNG rng(3);
  FlowGraph graph;
  const int w = 30, h = 20;
  for (int i = 0; i < w * h; ++i) graph.addNode(rng.uniform(0.f, 2.f), rng.uniform(0.f, 2.f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) graph.addEdge(y * w + x, y * w + x + 1, rng.uniform(0.f, 1.f));
      if (y + 1 < h) graph.addEdge(y * w + x, (y + 1) * w + x, rng.uniform(0.f, 1.f));
    }
  const auto a = minimumCut(graph, MaxFlowSolver::kOpenCv);
  const auto b = minimumCut(graph, MaxFlowSolver::kBoost);
  EXPECT_EQ(a, b);
  EXPECT_GT(std::count(a.begin(), a.end(), 1), 0);
  EXPECT_GT(std::count(a.begin(), a.end(), 0), 0);
}

TEST(MaxFlow, TwoNodeCutByHand) {
  // Node 0 strongly source, node 1 weakly sink, weak edge: labels (1, 0); strong edge: (1, 1).
  for (float edge : {0.5f, 10.f}) {
    FlowGraph graph;
    graph.addNode(5.f, 0.f);
    graph.addNode(0.f, 1.f);
    graph.addEdge(0, 1, edge);
    const auto side = minimumCut(graph, MaxFlowSolver::kOpenCv);
    EXPECT_EQ(side[0], 1);
    EXPECT_EQ(side[1], edge > 1.f ? 1 : 0) << "edge " << edge;
  }
}

}  // namespace
}  // namespace movseg
