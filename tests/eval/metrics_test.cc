// Each metric on hand-made masks whose scores are worked out by hand in the comments.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "eval/eval_fixture.h"
#include "eval/metrics.h"

namespace movseg {
namespace {

using test::rectMask;

const cv::Size kSmall(10, 10);
// 100x100: diagonal 141.42, tolerance ceil(0.008 * 141.42) = ceil(1.13) = 2 pixels.
const cv::Size kHundred(100, 100);

FrameScore counts(int frame, long tp, long fp, long fn, long tn) {
  FrameScore score;
  score.frame = frame;
  score.tp = tp;
  score.fp = fp;
  score.fn = fn;
  score.tn = tn;
  return score;
}

TEST(EvalMetrics, JOfTwoOverlappingSquares) {
  // 4x4 squares at (0,0) and (2,2) share a 2x2 corner: IoU = 4 / (16 + 16 - 4) = 1/7.
  const FrameScore score =
      scoreFrame(rectMask(kSmall, {2, 2, 4, 4}), rectMask(kSmall, {0, 0, 4, 4}));
  EXPECT_DOUBLE_EQ(score.j, 1.0 / 7);
  EXPECT_EQ(score.tp, 4);
  EXPECT_EQ(score.fp, 12);
  EXPECT_EQ(score.fn, 12);
  EXPECT_EQ(score.tn, 72);
}

TEST(EvalMetrics, BothEmptyScoresOne) {
  const cv::Mat empty = rectMask(kSmall, {});
  const FrameScore score = scoreFrame(empty, empty);
  EXPECT_EQ(score.j, 1);
  EXPECT_EQ(score.f, 1);
  EXPECT_EQ(score.error_rate, 0);
  EXPECT_EQ(score.precision(), 1);
  EXPECT_EQ(score.recall(), 1);
  EXPECT_EQ(score.f1(), 1);
}

TEST(EvalMetrics, ErrorRateIsMislabelledShareInPercent) {
  // Same squares as above: 12 false positives + 12 false negatives of 100 pixels = 24 %.
  const FrameScore score =
      scoreFrame(rectMask(kSmall, {2, 2, 4, 4}), rectMask(kSmall, {0, 0, 4, 4}));
  EXPECT_DOUBLE_EQ(score.error_rate, 24.0);
}

TEST(EvalMetrics, PixelPrecisionRecallF1) {
  // Prediction: the top half (8 px) of the 4x4 truth. tp 8, fp 0, fn 8: P = 1, R = 0.5,
  // F1 = 2 * 1 * 0.5 / 1.5 = 2/3.
  const FrameScore score =
      scoreFrame(rectMask(kSmall, {0, 0, 4, 2}), rectMask(kSmall, {0, 0, 4, 4}));
  EXPECT_DOUBLE_EQ(score.precision(), 1.0);
  EXPECT_DOUBLE_EQ(score.recall(), 0.5);
  EXPECT_DOUBLE_EQ(score.f1(), 2.0 / 3);
}

TEST(EvalMetrics, EmptySetConventions) {
  // Nothing predicted, something to find: P = 1, R = 0, F = 0.
  EXPECT_EQ(precisionRecall(0, 0, 0, 5).precision, 1);
  EXPECT_EQ(precisionRecall(0, 0, 0, 5).recall, 0);
  EXPECT_EQ(precisionRecall(0, 0, 0, 5).f(), 0);
  // Something predicted, nothing to find: P = 0, R = 1, F = 0.
  EXPECT_EQ(precisionRecall(0, 5, 0, 0).precision, 0);
  EXPECT_EQ(precisionRecall(0, 5, 0, 0).recall, 1);
  EXPECT_EQ(precisionRecall(0, 5, 0, 0).f(), 0);
  EXPECT_EQ(precisionRecall(0, 0, 0, 0).f(), 1);
}

TEST(EvalMetrics, BoundaryToleranceIsDavisFraction) {
  EXPECT_EQ(boundaryTolerance(kHundred), 2);
  // 854x480 (DAVIS 480p): diagonal 979.65, 0.008 * 979.65 = 7.84 -> 8.
  EXPECT_EQ(boundaryTolerance({854, 480}), 8);
}

TEST(EvalMetrics, BoundaryWithinToleranceMatches) {
  // Left half (columns 0-49): its boundary is column 49 (seg2bmap marks the last foreground
  // column). Columns 0-51 put the boundary at 51, 2 px away = the tolerance: all matched.
  const cv::Mat truth = rectMask(kHundred, {0, 0, 50, 100});
  EXPECT_DOUBLE_EQ(boundaryF(rectMask(kHundred, {0, 0, 52, 100}), truth), 1.0);
  // Columns 0-52: boundary 3 px away, beyond the tolerance: nothing matched.
  EXPECT_DOUBLE_EQ(boundaryF(rectMask(kHundred, {0, 0, 53, 100}), truth), 0.0);
}

TEST(EvalMetrics, BoundaryPartlyWithinTolerance) {
  // Truth: columns 0-49 -> boundary column 49, rows 0-99 (100 px).
  // Prediction: columns 0-49 in rows 0-49, columns 0-52 in rows 50-99. Its boundary: column 49
  // rows 0-49 (50 px), the step in row 49 at columns 50-52 (3 px), column 52 rows 50-99 (50 px):
  // 103 px. Within 2 px of the truth: column 49 and the step's columns 50, 51 -> 52 px.
  // Truth pixels within 2 px of the prediction: rows 0-49 and rows 50, 51 (1 and 2 px below
  // (49, 49)) -> 52 px. F = 2 * 52 / (103 + 100) = 104/203.
  cv::Mat pred = rectMask(kHundred, {0, 0, 50, 100});
  pred(cv::Rect(50, 50, 3, 50)).setTo(255);
  EXPECT_DOUBLE_EQ(boundaryF(pred, rectMask(kHundred, {0, 0, 50, 100})), 104.0 / 203);
}

// A mask of random discs and single pixels at 854x480 (tolerance 8 px, whose disk has corners
// a square would not) and at 100x100; the prediction the truth's discs moved by a few pixels,
// with speckle of its own.
std::pair<cv::Mat, cv::Mat> randomMasks(cv::Size size, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat truth = cv::Mat::zeros(size, CV_8U), pred = cv::Mat::zeros(size, CV_8U);
  for (int i = 0; i < 6; ++i) {
    const cv::Point centre(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const int radius = rng.uniform(2, size.height / 4);
    cv::circle(truth, centre, radius, 255, cv::FILLED);
    const cv::Point moved(rng.uniform(-10, 11), rng.uniform(-10, 11));
    cv::circle(pred, centre + moved, radius + rng.uniform(-3, 4), 255, cv::FILLED);
  }
  for (int i = 0; i < size.area() / 200; ++i) {
    pred.at<uchar>(rng.uniform(0, size.height), rng.uniform(0, size.width)) ^= 255;
  }
  return {pred, truth};
}

// DAVIS's f_measure, as the first implementation computed it by dilating both boundary maps
// with the disk whole (cv::dilate); the figures it gave on these masks.
TEST(EvalMetrics, BoundaryFOfRandomMasksIsTheDilationsFigure) {
  const std::pair<cv::Size, double> expected[] = {
      {{854, 480}, 0.39700231828650662},
      {{854, 480}, 0.40567666849898765},
      {{100, 100}, 0.24775660505523578}};
  uint64_t seed = 1;
  for (const auto& [size, f] : expected) {
    const auto [pred, truth] = randomMasks(size, seed++);
    EXPECT_DOUBLE_EQ(boundaryF(pred, truth), f) << size;
  }
}

TEST(EvalMetrics, BoundaryOfOneEmptyMaskScoresZero) {
  const cv::Mat square = rectMask(kHundred, {20, 20, 30, 30});
  const cv::Mat empty = rectMask(kHundred, {});
  EXPECT_EQ(boundaryF(square, empty), 0);
  EXPECT_EQ(boundaryF(empty, square), 0);
  EXPECT_EQ(boundaryF(empty, empty), 1);
}

TEST(EvalMetrics, IgnoredPixelsAreNotCounted) {
  // Truth: left half (50 px). Prediction: everything. Ignoring the right half leaves a perfect
  // prediction on the 50 counted pixels.
  const cv::Mat truth = rectMask(kSmall, {0, 0, 5, 10});
  const cv::Mat all = rectMask(kSmall, {0, 0, 10, 10});
  const FrameScore plain = scoreFrame(all, truth);
  EXPECT_DOUBLE_EQ(plain.j, 0.5);
  EXPECT_DOUBLE_EQ(plain.error_rate, 50.0);
  const FrameScore ignored = scoreFrame(all, truth, rectMask(kSmall, {5, 0, 5, 10}));
  EXPECT_EQ(ignored.j, 1);
  EXPECT_EQ(ignored.f, 1);
  EXPECT_EQ(ignored.error_rate, 0);
  EXPECT_EQ(ignored.tp + ignored.fp + ignored.fn + ignored.tn, 50);
}

TEST(EvalMetrics, MismatchedSizesThrow) {
  EXPECT_THROW(scoreFrame(rectMask({10, 10}, {}), rectMask({10, 11}, {})), std::invalid_argument);
}

TEST(EvalMetrics, SequenceMeansSkipTheFirstFrame) {
  SequenceScore sequence;
  sequence.first_frame = 3;
  FrameScore first = counts(3, 0, 100, 0, 0);  // all wrong, but not counted
  first.j = 0;
  first.f = 0;
  first.error_rate = 100;
  FrameScore a = counts(4, 4, 12, 12, 72);  // P 0.25, R 0.25
  a.j = 0.4;
  a.f = 0.2;
  a.error_rate = 24;
  FrameScore b = counts(5, 8, 0, 8, 84);  // P 1, R 0.5
  b.j = 0.8;
  b.f = 0.6;
  b.error_rate = 8;
  sequence.frames = {first, a, b};
  EXPECT_EQ(sequence.counted().size(), 2u);
  EXPECT_DOUBLE_EQ(sequence.meanJ(), 0.6);
  EXPECT_DOUBLE_EQ(sequence.meanF(), 0.4);
  EXPECT_DOUBLE_EQ(sequence.meanErrorRate(), 16.0);
  EXPECT_DOUBLE_EQ(sequence.recallJ(), 0.5);  // only 0.8 > 0.5
  // Summed counts tp 12, fp 12, fn 20: P = 12/24 = 0.5, R = 12/32 = 0.375,
  // F1 = 2 * 0.5 * 0.375 / 0.875 = 3/7 (the per-frame mean of P would be 0.625).
  EXPECT_DOUBLE_EQ(sequence.precision(), 0.5);
  EXPECT_DOUBLE_EQ(sequence.recall(), 0.375);
  EXPECT_DOUBLE_EQ(sequence.f1(), 3.0 / 7);
}

TEST(EvalMetrics, SequenceWithoutCountedFramesIsNaN) {
  SequenceScore sequence;
  sequence.frames = {counts(0, 1, 0, 0, 0)};  // the first frame only
  EXPECT_TRUE(std::isnan(sequence.meanJ()));
  EXPECT_TRUE(std::isnan(sequence.recallJ()));
  EXPECT_TRUE(std::isnan(sequence.precision()));
}

TEST(EvalMetrics, MeanOverSequencesWeighsSequencesEqually) {
  ScoreSummary a;
  a.frames = 10;
  a.j = 0.2;
  a.precision = 1;
  ScoreSummary b;
  b.frames = 30;
  b.j = 0.6;
  b.precision = 0.5;
  const ScoreSummary mean = meanOverSequences({a, b}, "mean");
  EXPECT_EQ(mean.name, "mean");
  EXPECT_EQ(mean.frames, 40);
  EXPECT_DOUBLE_EQ(mean.j, 0.4);
  EXPECT_DOUBLE_EQ(mean.precision, 0.75);
}

}  // namespace
}  // namespace movseg
