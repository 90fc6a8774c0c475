// The OpenCV drop-in: cv::BackgroundSubtractor::apply gives exactly Segmenter::process's masks.
#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "movseg/background_subtractor.h"
#include "movseg/segmenter.h"
#include "synth/synth.h"
#include "test_support.h"

namespace movseg {
namespace {

SynthSequence shortSequence() {
  SynthOptions options;
  options.frames = 6;
  options.size = {160, 120};
  return SynthSequence(options);
}

TEST(BackgroundSubtractor, GivesTheSegmentersMasksAndCompensatedFrame) {
  const SynthSequence sequence = shortSequence();
  Segmenter segmenter;
  const cv::Ptr<cv::BackgroundSubtractor> subtractor = createMovingCameraSubtractor(Params());
  for (int t = 0; t < sequence.size(); ++t) {
    const cv::Mat frame = sequence.frame(t).frame;
    const cv::Mat expected = segmenter.process(frame).mask;
    cv::Mat mask, background;
    subtractor->apply(frame, mask);
    subtractor->getBackgroundImage(background);
    ASSERT_EQ(mask.size(), expected.size()) << "frame " << t;
    EXPECT_EQ(cv::countNonZero(mask != expected), 0) << "frame " << t;
    const cv::Mat compensated = segmenter.compensatedPreviousFrame();
    ASSERT_EQ(background.empty(), t == 0) << "frame " << t;
    if (t > 0) {
      EXPECT_EQ(cv::norm(background, compensated, cv::NORM_INF), 0) << "frame " << t;
    }
  }
}

// There is no background model to learn, so MOG2-style learning rates change nothing.
TEST(BackgroundSubtractor, IgnoresTheLearningRate) {
  const SynthSequence sequence = shortSequence();
  const cv::Ptr<cv::BackgroundSubtractor> a = createMovingCameraSubtractor();
  const cv::Ptr<cv::BackgroundSubtractor> b = createMovingCameraSubtractor();
  for (int t = 0; t < 3; ++t) {
    cv::Mat mask_a, mask_b;
    a->apply(sequence.frame(t).frame, mask_a, -1);
    b->apply(sequence.frame(t).frame, mask_b, 0);
    EXPECT_EQ(cv::countNonZero(mask_a != mask_b), 0) << "frame " << t;
    // The first frame's mask is empty; equal empty masks would prove nothing.
    if (t > 0) {
      ASSERT_GT(cv::countNonZero(mask_a), 0) << "frame " << t;
    }
  }
}

// The region is the Segmenter's: its masks, nothing in the region (where the clip's movers do
// show without it), and a region of another type refused when the subtractor is made.
TEST(BackgroundSubtractor, TakesAnIgnoredRegionForItsLife) {
  const SynthSequence sequence = shortSequence();
  cv::Mat region(30, 40, CV_8U, cv::Scalar(0));
  region.colRange(0, 20).setTo(255);  // the left half, at any size
  Segmenter segmenter;
  segmenter.setIgnoredRegion(region);
  const cv::Ptr<cv::BackgroundSubtractor> told = createMovingCameraSubtractor(Params(), region);
  const cv::Ptr<cv::BackgroundSubtractor> untold = createMovingCameraSubtractor();
  int moving_in_region_untold = 0;
  for (int t = 0; t < sequence.size(); ++t) {
    const cv::Mat frame = sequence.frame(t).frame;
    const cv::Mat left = cv::Mat(frame.size(), CV_8U, cv::Scalar(0));
    left.colRange(0, frame.cols / 2).setTo(255);
    cv::Mat mask, untold_mask;
    told->apply(frame, mask);
    untold->apply(frame, untold_mask);
    EXPECT_EQ(cv::countNonZero(mask != segmenter.process(frame).mask), 0) << "frame " << t;
    EXPECT_EQ(cv::countNonZero(mask & left), 0) << "frame " << t;
    moving_in_region_untold += cv::countNonZero(untold_mask & left);
  }
  EXPECT_GT(moving_in_region_untold, 100);
  EXPECT_THROW(createMovingCameraSubtractor(Params(), cv::Mat(4, 4, CV_32F, cv::Scalar(1))),
               std::invalid_argument);
}

// Its name is a key cv::Algorithm::save() can write (a '.' in it made save() throw).
TEST(BackgroundSubtractor, RejectsEmptyFramesAndNamesItselfAsSaveWrites) {
  const cv::Ptr<cv::BackgroundSubtractor> subtractor = createMovingCameraSubtractor();
  cv::Mat mask;
  EXPECT_THROW(subtractor->apply(cv::Mat(), mask), std::invalid_argument);
  EXPECT_EQ(subtractor->getDefaultName(), "movseg_MovingCameraSubtractor");
  const test::TempDir dir;
  EXPECT_NO_THROW(subtractor->save(dir / "subtractor.yml"));
}

// Threads sharing one subtractor take turns (they corrupted its state: MOG2 crashes so): the
// masks are those of one thread applying the same frames, in whatever order they came.
TEST(BackgroundSubtractor, ThreadsSharingOneTakeTurns) {
  const cv::Ptr<cv::BackgroundSubtractor> shared = createMovingCameraSubtractor();
  cv::Mat frame(120, 160, CV_8UC3);
  cv::randu(frame, 0, 255);
  std::vector<std::thread> threads;
  std::atomic<int> done{0};
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 25; ++i) {
        cv::Mat mask;
        shared->apply(frame, mask);
        cv::Mat background;
        shared->getBackgroundImage(background);
        if (mask.size() == frame.size() && cv::countNonZero(mask) == 0) ++done;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(done.load(), 100);  // a still frame: nothing moves, every time
  // And the state they shared is whole: the background is the frame, and a patch moving over
  // it next is found, with the masks, bit for bit, of one subtractor that applied the same
  // 100 frames on one thread (a race that left its colour model, memory or previous frame
  // different would show there, where an empty mask of a still frame need not).
  cv::Mat background;
  shared->getBackgroundImage(background);
  EXPECT_EQ(cv::norm(background, frame, cv::NORM_INF), 0);
  const cv::Ptr<cv::BackgroundSubtractor> alone = createMovingCameraSubtractor();
  cv::Mat mask, expected;
  for (int i = 0; i < 100; ++i) alone->apply(frame, expected);
  for (const int step : {6, 12, 18}) {
    cv::Mat moved = frame.clone();
    frame(cv::Rect(30, 30, 60, 60)).copyTo(moved(cv::Rect(30 + step, 30, 60, 60)));
    shared->apply(moved, mask);
    alone->apply(moved, expected);
    EXPECT_EQ(cv::norm(mask, expected, cv::NORM_INF), 0) << "step " << step;
  }
  EXPECT_GT(cv::countNonZero(mask), 1800);  // half the patch
}

}  // namespace
}  // namespace movseg
