// The grid energy and its solves: the coarse energy prices block labellings exactly as the fine
// one does, the exact reduction agrees with the full max-flow, coarse to fine finds a clean
// boundary exactly.
#include <gtest/gtest.h>

#include <limits>

#include <opencv2/imgproc.hpp>

#include "cut/grid_energy.h"

namespace movseg {
namespace {

GridEnergy randomEnergy(cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  GridEnergy e{cv::Mat(size, CV_32F), cv::Mat(size, CV_32F), cv::Mat(size, CV_32F),
               cv::Mat(size, CV_32F)};
  for (cv::Mat* m : {&e.cost_fg, &e.cost_bg}) rng.fill(*m, cv::RNG::UNIFORM, 0.f, 2.f);
  for (cv::Mat* m : {&e.right, &e.down}) rng.fill(*m, cv::RNG::UNIFORM, 0.f, 1.f);
  e.right.col(size.width - 1).setTo(0);
  e.down.row(size.height - 1).setTo(0);
  return e;
}

// The energy of a 0/255 labelling.
double energyOf(const GridEnergy& e, const cv::Mat& labels) {
  double total = 0;
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const bool fg = labels.at<uchar>(y, x) != 0;
      total += fg ? e.cost_fg.at<float>(y, x) : e.cost_bg.at<float>(y, x);
      if (x + 1 < labels.cols && fg != (labels.at<uchar>(y, x + 1) != 0)) total += e.right.at<float>(y, x);
      if (y + 1 < labels.rows && fg != (labels.at<uchar>(y + 1, x) != 0)) total += e.down.at<float>(y, x);
    }
  }
  return total;
}

TEST(GridEnergy, BlocksCostWhatTheirPixelsCost) {
  for (const cv::Size size : {cv::Size(16, 12), cv::Size(15, 9)}) {  // even and odd sides
    const GridEnergy fine = randomEnergy(size, 1);
    const GridEnergy coarse = coarsened(fine);
    cv::Mat blocks(coarse.cost_fg.size(), CV_8U);
    cv::RNG(2).fill(blocks, cv::RNG::UNIFORM, 0, 2);
    blocks *= 255;
    cv::Mat pixels(size, CV_8U);
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) pixels.at<uchar>(y, x) = blocks.at<uchar>(y / 2, x / 2);
    }
    EXPECT_NEAR(energyOf(coarse, blocks), energyOf(fine, pixels), 1e-3) << size;
  }
}

TEST(GridEnergy, TheExactReductionKeepsTheMinimum) {
  const GridEnergy e = randomEnergy({40, 30}, 3);
  const cv::Mat all_free = cv::Mat::zeros(30, 40, CV_8U);
  int whole = 0, reduced = 0;
  const cv::Mat full = labelFreePixels(e, all_free, MaxFlowSolver::kOpenCv, &whole);
  cv::Mat decided;
  decidedPixels(e, &decided);
  const cv::Mat part = labelFreePixels(e, decided, MaxFlowSolver::kOpenCv, &reduced);
  EXPECT_EQ(whole, 1200);
  EXPECT_LT(reduced, whole);
  EXPECT_NEAR(energyOf(e, part), energyOf(e, full), 1e-3);
}

// The grid's own max-flow finds a minimum of the same energy as OpenCV's general one, with the
// whole grid free and with pixels fixed by the exact reduction, on grids where the unary or the
// edges dominate; on these energies the minimum is unique, so the labels are the same too.
TEST(GridEnergy, TheGridSolverFindsTheMinimumOpenCvFinds) {
  for (const float edge_scale : {0.3f, 1.f, 3.f}) {
    for (const std::uint64_t seed : {4u, 5u, 6u}) {
      GridEnergy e = randomEnergy({37, 23}, seed);
      e.right *= edge_scale;
      e.down *= edge_scale;
      cv::Mat decided;
      decidedPixels(e, &decided);
      for (const cv::Mat& state : {cv::Mat(cv::Mat::zeros(23, 37, CV_8U)), decided}) {
        int general_nodes = 0, grid_nodes = 0;
        const cv::Mat general = labelFreePixels(e, state, MaxFlowSolver::kOpenCv, &general_nodes);
        const cv::Mat grid = labelFreePixels(e, state, MaxFlowSolver::kGrid, &grid_nodes);
        EXPECT_EQ(grid_nodes, general_nodes);
        EXPECT_NEAR(energyOf(e, grid), energyOf(e, general), 1e-3) << edge_scale << " " << seed;
        EXPECT_EQ(cv::countNonZero(grid != general), 0) << edge_scale << " " << seed;
      }
    }
  }
}

// A NaN among the capacities never saturates: the grid solver stops with an error, as
// OpenCV's refuses such an edge, instead of pushing along the same path for ever.
TEST(GridEnergy, TheGridSolverRefusesANanCapacity) {
  GridEnergy e = randomEnergy({12, 8}, 7);
  e.cost_bg.setTo(0);
  e.cost_fg.setTo(0);
  e.cost_bg.at<float>(3, 4) = 1.f;  // a source there, a sink beside it, a NaN edge between
  e.cost_fg.at<float>(3, 5) = 1.f;
  e.right.at<float>(3, 4) = std::numeric_limits<float>::quiet_NaN();
  int nodes = 0;
  EXPECT_THROW(labelFreePixels(e, cv::Mat::zeros(8, 12, CV_8U), MaxFlowSolver::kGrid, &nodes),
               cv::Exception);
}

// Two flat halves with a boundary at an odd column: the blocks place it within a pixel, the
// refinement puts it back exactly.
TEST(GridEnergy, CoarseToFineFindsAnOddBoundaryExactly) {
  const cv::Size size(41, 20);
  GridEnergy e{cv::Mat(size, CV_32F), cv::Mat(size, CV_32F), cv::Mat(size, CV_32F, 0.2f),
               cv::Mat(size, CV_32F, 0.2f)};
  cv::Mat truth = cv::Mat::zeros(size, CV_8U);
  truth.colRange(17, 41).setTo(255);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const bool fg = x >= 17;
      e.cost_fg.at<float>(y, x) = fg ? 0.f : 0.3f;
      e.cost_bg.at<float>(y, x) = fg ? 0.3f : 0.f;
    }
  }
  e.right.col(40).setTo(0);
  e.down.row(19).setTo(0);
  int nodes = 0;
  const cv::Mat labels = labelCoarseToFine(e, cv::Mat::zeros(size, CV_8U), 2, MaxFlowSolver::kOpenCv, &nodes);
  EXPECT_EQ(cv::countNonZero(labels != truth), 0);
  EXPECT_LT(nodes, size.area());
}

}  // namespace
}  // namespace movseg
