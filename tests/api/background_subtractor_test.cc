// The OpenCV drop-in: cv::BackgroundSubtractor::apply gives exactly Segmenter::process's masks.
#include <gtest/gtest.h>

#include "movseg/background_subtractor.h"
#include "movseg/segmenter.h"
#include "synth/synth.h"

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
  }
}

TEST(BackgroundSubtractor, RejectsEmptyFramesAndNamesItself) {
  const cv::Ptr<cv::BackgroundSubtractor> subtractor = createMovingCameraSubtractor();
  cv::Mat mask;
  EXPECT_THROW(subtractor->apply(cv::Mat(), mask), std::invalid_argument);
  EXPECT_EQ(subtractor->getDefaultName(), "movseg.MovingCameraSubtractor");
}

}  // namespace
}  // namespace movseg
