// The bugs fuzz/ found, one readable test each; their fuzz inputs are in fuzz/corpus/ as
// regression-* (replayed by fuzz_corpus_test.cc).
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "cut/max_flow.h"
#include "eval/dataset.h"
#include "io/frame_source.h"
#include "motion/motion_fixture.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

// regression-float64-frame: cv::patchNaNs takes CV_32F only, so 64-bit frames threw
// cv::Exception out of process().
TEST(FuzzRegressions, SixtyFourBitFloatFramesWithNanAreAccepted) {
  test::PairSpec spec;
  spec.object_fraction = 0.15;  // a mover, for masks that say something
  const test::FramePair pair = test::makePair(spec);
  Segmenter as_float, as_double, as_zero;
  cv::Mat zeroed_mask;
  for (const cv::Mat& frame : {pair.prev, pair.cur}) {
    cv::Mat f32, f64, zeroed;
    frame.convertTo(f32, CV_32FC3, 1.0 / 255.0);
    f32.copyTo(zeroed);
    zeroed(cv::Rect(0, 0, 10, 10)).setTo(0);
    f32(cv::Rect(0, 0, 10, 10)).setTo(std::numeric_limits<float>::quiet_NaN());
    f32.convertTo(f64, CV_64FC3);
    const Result a = as_float.process(f32);
    const Result b = as_double.process(f64);
    test::expectValidResult(b, frame.size());
    EXPECT_EQ(cv::countNonZero(a.mask != b.mask), 0);
    // NaN pixels read as 0 (README): the masks of the frame with 0 there.
    zeroed_mask = as_zero.process(zeroed).mask;
    EXPECT_EQ(cv::countNonZero(a.mask != zeroed_mask), 0);
  }
  EXPECT_GT(cv::countNonZero(zeroed_mask), 0);  // masks that say something
}

// regression-feature-rounds-off-edge: with the segmentation scale below the alignment scale,
// a feature by the right or bottom edge rounded to the pixel past the segmentation image and
// its seed was written out of bounds (caught by the sanitizer build).
TEST(FuzzRegressions, SegmentationScaleBelowAlignmentScaleKeepsSeedsInside) {
  test::PairSpec spec;
  spec.object_fraction = 0.15;
  const test::FramePair pair = test::makePair(spec);
  Params params;
  params.method = Method::kPaper;  // its seeds
  // Alignment at 320: features keep 6 px from the edges there, under half a pixel at 16x12, so
  // those by the right or bottom edge round past it.
  params.segmentation_width = 16;
  Segmenter segmenter(params);
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  test::expectValidResult(r, pair.cur.size());
  EXPECT_GT(r.diagnostics.foreground_seeds + r.diagnostics.background_seeds, 0);
  // Outside the sanitizer build the write itself shows nothing: each feature (full resolution)
  // must lie in the frame, and its seed, rounded at the segmentation size, in that; some lie on
  // its last column or row, where the rounding went past.
  const cv::Size seg(16, 12);
  const double scale = static_cast<double>(seg.width) / pair.cur.cols;
  int on_the_edge = 0;
  for (const Feature& feature : r.features) {
    const cv::Point2f p = feature.position;
    EXPECT_TRUE(p.x >= 0 && p.x < pair.cur.cols && p.y >= 0 && p.y < pair.cur.rows) << p;
    const cv::Point seed(cvRound(p.x * scale), cvRound(p.y * scale));
    EXPECT_TRUE(cv::Rect(cv::Point(), seg).contains(seed)) << p << " -> " << seed;
    on_the_edge += seed.x == seg.width - 1 || seed.y == seg.height - 1;
  }
  EXPECT_GT(on_the_edge, 0);
}

// regression-cut-without-edges: free pixels with no free neighbour make a graph without edges,
// on which OpenCV's GCGraph asserts; each node then takes its stronger terminal.
TEST(FuzzRegressions, MaxFlowGraphWithoutEdges) {
  FlowGraph graph;
  graph.addNode(2.f, 1.f);
  graph.addNode(0.f, 5.f);
  graph.addNode(1.f, 1.f);
  for (const MaxFlowSolver solver : {MaxFlowSolver::kOpenCv, MaxFlowSolver::kBoost}) {
    EXPECT_EQ(minimumCut(graph, solver), (std::vector<std::uint8_t>{1, 0, 0}));
    EXPECT_TRUE(minimumCut(FlowGraph(), solver).empty());
  }
}

// regression-huge-image-header: cv::imread throws cv::Exception (instead of returning an empty
// image) when a header claims a width beyond OpenCV's limit; the readers promise
// std::runtime_error naming the file, and the CLI a one-line error.
TEST(FuzzRegressions, ImageHeaderBeyondOpenCvLimitsIsAnUnreadableFile) {
  test::TempDir dir;
  const std::string path = dir / "frames/00000.pgm";
  std::filesystem::create_directories(dir / "frames");
  std::ofstream(path, std::ios::binary) << "P5\n2000000 1\n255\n" << std::string(16, '\x7f');
  EXPECT_THROW(cv::imread(path), cv::Exception);  // what made the file special

  EXPECT_THROW(readMask(path), std::runtime_error);
  const std::unique_ptr<FrameSource> source = FrameSource::open(dir / "frames");
  cv::Mat frame;
  EXPECT_THROW(source->read(&frame), std::runtime_error);
  const auto run = test::runCli("segment " + (dir / "frames") + " -o " + (dir / "out") + " -q");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.output, "movseg: error: cannot decode image '" + path + "'\n");
}

}  // namespace
}  // namespace movseg
