// The public API: Segmenter::process on any supported frame, online, with diagnostics.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "motion/motion_fixture.h"
#include "movseg/segmenter.h"
#include "test_support.h"

namespace movseg {
namespace {

double iou(const cv::Mat& a, const cv::Mat& b) {
  const double inter = cv::countNonZero(a & b), uni = cv::countNonZero(a | b);
  return uni > 0 ? inter / uni : 1.0;
}

void expectBinaryMaskOfSize(const Result& r, cv::Size size) {
  ASSERT_EQ(r.mask.type(), CV_8U);
  ASSERT_EQ(r.mask.size(), size);
  EXPECT_EQ(cv::countNonZero((r.mask != 0) & (r.mask != 255)), 0);
}

test::FramePair movingPair() {
  test::PairSpec spec;
  spec.camera = test::similarityAboutCentre(spec.size, 1.5, 1.01, {3, -2});
  spec.object_fraction = 0.15;
  return test::makePair(spec);
}

TEST(Segmenter, FirstFrameIsEmptyThenTheObjectIsFound) {
  const test::FramePair pair = movingPair();
  Segmenter segmenter;
  const Result first = segmenter.process(pair.prev);
  expectBinaryMaskOfSize(first, pair.prev.size());
  EXPECT_TRUE(first.diagnostics.first_frame);
  EXPECT_EQ(cv::countNonZero(first.mask), 0);

  const Result second = segmenter.process(pair.cur);
  expectBinaryMaskOfSize(second, pair.cur.size());
  EXPECT_FALSE(second.diagnostics.first_frame);
  EXPECT_GT(iou(second.mask, pair.cur_mask), 0.85);
  EXPECT_GT(second.diagnostics.foreground_seeds, 5);
  EXPECT_GT(second.diagnostics.background_seeds, 50);
  EXPECT_GT(second.diagnostics.matches, 50);
  EXPECT_GT(second.diagnostics.timings.total_ms, 0.0);
  EXPECT_FALSE(second.features.empty());
}

TEST(Segmenter, ReportsTheCameraModelInFullResolutionPixels) {
  test::PairSpec spec;
  spec.size = {640, 480};
  spec.camera = test::similarityAboutCentre(spec.size, 1, 1.0, {8, -4});
  spec.object_fraction = 0.1;
  const test::FramePair pair = test::makePair(spec);
  Segmenter segmenter;
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  EXPECT_TRUE(r.diagnostics.model_is_affine);
  EXPECT_LT(test::cornerError(r.diagnostics.model, spec.camera, spec.size), 1.0);
}

cv::Mat secondMask(const cv::Mat& prev, const cv::Mat& cur) {
  Segmenter segmenter;
  segmenter.process(prev);
  const Result r = segmenter.process(cur);
  expectBinaryMaskOfSize(r, cur.size());
  return r.mask;
}

// BGRA and 16-bit frames carry the same picture, so they give the BGR frames' mask exactly;
// grey frames lose the colour the GMMs and the geodesic metric use, and do less well.
TEST(Segmenter, AcceptsGreyBgraAnd16BitFrames) {
  const test::FramePair pair = movingPair();
  const cv::Mat bgr_mask = secondMask(pair.prev, pair.cur);
  cv::Mat a, b;
  cv::cvtColor(pair.prev, a, cv::COLOR_BGR2BGRA);
  cv::cvtColor(pair.cur, b, cv::COLOR_BGR2BGRA);
  EXPECT_EQ(cv::countNonZero(secondMask(a, b) != bgr_mask), 0);
  pair.prev.convertTo(a, CV_16UC3, 256);
  pair.cur.convertTo(b, CV_16UC3, 256);
  EXPECT_EQ(cv::countNonZero(secondMask(a, b) != bgr_mask), 0);
  cv::cvtColor(pair.prev, a, cv::COLOR_BGR2GRAY);
  cv::cvtColor(pair.cur, b, cv::COLOR_BGR2GRAY);
  EXPECT_GT(iou(secondMask(a, b), pair.cur_mask), 0.4);
}

TEST(Segmenter, RejectsEmptyFramesAndUnsupportedChannelCounts) {
  Segmenter segmenter;
  EXPECT_THROW(segmenter.process(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(segmenter.process(cv::Mat(8, 8, CV_8UC2, cv::Scalar(1, 2))), std::invalid_argument);
}

TEST(Segmenter, InvalidParamsThrowAtConstruction) {
  Params params;
  params.gmm_clusters = 0;
  EXPECT_THROW(Segmenter{params}, std::invalid_argument);
}

TEST(Segmenter, SizeChangeResetsInsteadOfFailing) {
  const test::FramePair pair = movingPair();
  Segmenter segmenter;
  segmenter.process(pair.prev);
  cv::Mat smaller;
  cv::resize(pair.cur, smaller, {160, 120});
  const Result r = segmenter.process(smaller);
  expectBinaryMaskOfSize(r, smaller.size());
  EXPECT_TRUE(r.diagnostics.reset);
  EXPECT_TRUE(r.diagnostics.first_frame);
}

TEST(Segmenter, TinyAndDegenerateFramesGiveValidMasks) {
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(2, 2), cv::Size(7, 1000), cv::Size(1000, 7),
                              cv::Size(17, 17)}) {
    Segmenter segmenter;
    const cv::Mat a = test::texture(size, 1), b = test::texture(size, 2);
    for (const cv::Mat& frame : {a, b, a}) {
      const Result r = segmenter.process(frame);
      expectBinaryMaskOfSize(r, size);
    }
  }
}

TEST(Segmenter, StaticCameraModeSkipsAlignment) {
  test::PairSpec spec;
  spec.object_fraction = 0.15;
  const test::FramePair pair = test::makePair(spec);  // identity camera
  Params params;
  params.static_camera = true;
  Segmenter segmenter(params);
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  EXPECT_EQ(r.diagnostics.model, cv::Matx33d::eye());
  EXPECT_EQ(r.diagnostics.matches, 0);
  EXPECT_GT(iou(r.mask, pair.cur_mask), 0.85);
}

// A video loop reuses one buffer for every frame; the segmenter must keep its own copy of the
// previous frame, or the next call would compare the new frame with itself.
TEST(Segmenter, CallerReusingTheFrameBufferChangesNothing) {
  const test::FramePair pair = movingPair();
  Segmenter fresh, reused;
  cv::Mat buffer;
  for (const cv::Mat& frame : {pair.prev, pair.cur}) {
    frame.copyTo(buffer);
    const cv::Mat expected = fresh.process(frame.clone()).mask;
    const cv::Mat got = reused.process(buffer).mask;
    EXPECT_EQ(cv::countNonZero(expected != got), 0);
  }
  EXPECT_GT(cv::countNonZero(fresh.process(pair.prev).mask), 0);
}

TEST(Segmenter, SameInputGivesBitIdenticalMasks) {
  const test::FramePair pair = movingPair();
  auto run = [&] {
    Segmenter segmenter;
    segmenter.process(pair.prev);
    return segmenter.process(pair.cur).mask;
  };
  EXPECT_EQ(cv::countNonZero(run() != run()), 0);
}

TEST(Segmenter, DebugPicturesWhenAsked) {
  const test::FramePair pair = movingPair();
  Params params;
  params.debug_images = true;
  Segmenter segmenter(params);
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  for (const char* name : {"matches", "difference", "features", "features_refined", "confidence", "mask"}) {
    ASSERT_TRUE(r.debug.count(name)) << name;
    EXPECT_FALSE(r.debug.at(name).empty()) << name;
  }
  EXPECT_FALSE(segmenter.compensatedPreviousFrame().empty());
}

}  // namespace
}  // namespace movseg
