// Allocations per frame in the steady state of Segmenter::process, for a fixed frame size.
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "alloc/counting_malloc.h"
#include "cut/grid_energy.h"
#include "cut/grid_max_flow.h"
#include "flow/dense_flow.h"
#include "movseg/segmenter.h"
#include "synth/synth.h"

namespace movseg {
namespace {

TEST(Allocations, TheCounterSeesNewVectorsAndOpenCvBuffers) {
  cv::Mat image(48, 64, CV_8UC3);  // OpenCV's first allocation sets up more than the buffer
  std::int64_t after_int = 0, after_vector = 0, after_mat = 0, after_reuse = 0;
  {
    test::CountAllocations counter;
    auto one = std::make_unique<int>(1);
    after_int = counter.count();
    std::vector<double> values(1000);
    after_vector = counter.count();
    image.create(480, 640, CV_8UC3);
    after_mat = counter.count();
    image.create(480, 640, CV_8UC3);  // the same size and type: reused
    after_reuse = counter.count();
  }
  EXPECT_EQ(after_int, 1);
  EXPECT_EQ(after_vector, 2);
  EXPECT_GT(after_mat, after_vector);
  EXPECT_EQ(after_reuse, after_mat);
}

// A disc that prefers the foreground, on a background that prefers the background.
GridEnergy discEnergy(cv::Size size) {
  cv::Mat preference(size, CV_32F, cv::Scalar(-0.5));
  cv::circle(preference, {size.width / 2, size.height / 2}, size.height / 3, cv::Scalar(0.5), -1);
  return {cv::max(-preference, 0.0), cv::max(preference, 0.0),
          cv::Mat(size, CV_32F, cv::Scalar(1)), cv::Mat(size, CV_32F, cv::Scalar(1))};
}

TEST(Allocations, TheGridMaxFlowKeepsItsNodesBetweenCalls) {
  const GridEnergy energy = discEnergy({320, 240});
  const cv::Mat all_free = cv::Mat::zeros(240, 320, CV_8U);
  GridMaxFlow max_flow;
  int nodes = 0;
  cv::Mat first, second;
  max_flow.label(energy, all_free, &nodes, &first);
  ASSERT_GT(cv::countNonZero(first), 0);
  second.create(first.size(), CV_8U);
  test::CountAllocations counter;
  max_flow.label(energy, all_free, &nodes, &second);
  EXPECT_EQ(counter.count(), 0);
  EXPECT_EQ(cv::countNonZero(first != second), 0);
}

// The dense flow keeps its frames' pyramids and its buffers between calls: at a fixed size, a
// frame costs no allocation of its own once two have passed.
TEST(Allocations, DenseFlowKeepsItsBuffersBetweenFrames) {
  SynthOptions clip;
  clip.frames = 8;
  const SynthSequence sequence(clip);
  std::vector<cv::Mat> frames;
  for (int t = 0; t < sequence.size(); ++t) {
    frames.emplace_back();
    cv::cvtColor(sequence.frame(t).frame, frames.back(), cv::COLOR_BGR2GRAY);
  }
  DenseFlow flow(Params().flow_finest_scale);
  cv::Mat flows[2];  // two in flight, as the pipeline keeps them
  for (size_t t = 0; t < 4; ++t) flow.next(frames[t], &flows[t % 2]);
  test::CountAllocations counter;
  for (size_t t = 4; t < frames.size(); ++t) flow.next(frames[t], &flows[t % 2]);
  std::printf("dense flow: %.1f allocations per frame\n", counter.count() / 4.0);
  EXPECT_EQ(counter.count(), 0);
  // And the flow was computed: the last pair's is that of a flow started afresh on the same
  // frames, and the camera's pan shows in it.
  const cv::Mat& last = flows[(frames.size() - 1) % 2];
  DenseFlow fresh(Params().flow_finest_scale);
  cv::Mat expected;
  for (const cv::Mat& frame : frames) fresh.next(frame, &expected);
  ASSERT_EQ(last.type(), CV_32FC2);
  EXPECT_EQ(last.size(), frames[0].size());
  EXPECT_EQ(cv::norm(last, expected, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(last, cv::NORM_L1) / last.total(), 0.5);  // px per pixel
}

struct Counted {
  double per_frame = 0;
  Result last;  // of one more frame after the counted ones: what the counted frames went through
};

// OpenCV's parallel loops run on the calling thread while it lives. A worker thread sets up its
// thread-local state (cv::theRNG()) the first time the scheduler gives it a loop, which on a
// loaded machine can be after the warm-up frames (a flaky count of 0.2 a frame). The buffers a
// loop allocates per call are allocated by its body on whatever thread runs it: counted either way.
class OneOpenCvThread {
 public:
  OneOpenCvThread() : threads_(cv::getNumThreads()) { cv::setNumThreads(1); }
  ~OneOpenCvThread() { cv::setNumThreads(threads_); }
  OneOpenCvThread(const OneOpenCvThread&) = delete;
  OneOpenCvThread& operator=(const OneOpenCvThread&) = delete;

 private:
  int threads_;
};

// Allocations per frame of a Segmenter with `params` on a 320x240 clip, after the first frames
// have sized every buffer.
// `framed`: the frames letterboxed (black bars found on every frame; no wider than the working
// width, whose resizes allocate) and a timestamp's box ignored.
Counted allocationsPerFrame(const Params& params, bool framed = false) {
  const OneOpenCvThread one_thread;
  SynthOptions clip;
  clip.frames = 24;
  const SynthSequence sequence(clip);
  std::vector<cv::Mat> frames;
  for (int t = 0; t < sequence.size(); ++t) {
    cv::Mat frame = sequence.frame(t).frame;
    if (framed) cv::copyMakeBorder(frame, frame, 40, 40, 0, 0, cv::BORDER_CONSTANT, cv::Scalar());
    frames.push_back(frame);
  }
  Segmenter segmenter(params);
  if (framed) {
    cv::Mat timestamp = cv::Mat::zeros(frames[0].size(), CV_8U);
    timestamp(cv::Rect(8, 48, 100, 12)).setTo(255);
    segmenter.setIgnoredRegion(timestamp);
  }
  constexpr int kWarmUp = 8;
  for (int t = 0; t < kWarmUp; ++t) segmenter.process(frames[static_cast<size_t>(t)]);
  // The last frame's result is kept, outside the count: a result held keeps its mask out of the
  // pool the segmenter draws from.
  const size_t counted = frames.size() - 1;
  Counted out;
  {
    test::CountAllocations counter;
    for (size_t t = kWarmUp; t < counted; ++t) segmenter.process(frames[t]);
    out.per_frame = static_cast<double>(counter.count()) / static_cast<double>(counted - kWarmUp);
  }
  out.last = segmenter.process(frames.back());
  return out;
}

// None (issue 13; 554 before, docs/design.md, "Speed of dense"): every stage keeps its buffers,
// its RANSACs and its scratch from one frame to the next, the result's mask comes from a pool
// the caller gives back by letting the result go, and the OpenCV calls that allocate on every
// call (cv::eigen, getPerspectiveTransform, filter engines, resizes by two, operations with a
// scalar) are replaced by code of our own with the same results.
TEST(Allocations, DenseMakesNoAllocationsPerFrame) {
  const Counted dense = allocationsPerFrame(Params());
  std::printf("dense: %.1f allocations per frame\n", dense.per_frame);
  EXPECT_EQ(dense.per_frame, 0.0);
  // The whole pipeline ran, up to a mask (a stage that gave up early allocates nothing either).
  EXPECT_GT(cv::countNonZero(dense.last.mask), 0);
  EXPECT_FALSE(dense.last.diagnostics.black_bars);
}

// Nor with the frame's colour histograms alone (colour_cell 0; the default's cells' tables are
// laid on the first frame of a size).
TEST(Allocations, DenseWithoutColourCellsMakesNoAllocationsPerFrame) {
  Params params;
  params.colour_cell = 0;
  const Counted frame_only = allocationsPerFrame(params);
  std::printf("dense, no colour cells: %.1f allocations per frame\n", frame_only.per_frame);
  EXPECT_EQ(frame_only.per_frame, 0.0);
  EXPECT_GT(cv::countNonZero(frame_only.last.mask), 0);
}

// Nor with black bars and an ignored region: the region is scaled, and its margin grown, from
// buffers kept, the margin only when the region changes.
TEST(Allocations, DenseWithBlackBarsAndAnIgnoredRegionMakesNoAllocationsPerFrame) {
  const Counted framed = allocationsPerFrame(Params(), true);
  std::printf("dense, framed: %.1f allocations per frame\n", framed.per_frame);
  EXPECT_EQ(framed.per_frame, 0.0);
  // The path this names was taken: the bars were found, and a mask came out.
  EXPECT_TRUE(framed.last.diagnostics.black_bars);
  EXPECT_GT(cv::countNonZero(framed.last.mask), 0);
}

}  // namespace
}  // namespace movseg
