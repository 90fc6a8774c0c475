// The dense method end to end: it finds movers on scenes unlike DAVIS (camouflaged, noisy,
// drifting gain), it is causal, and its memory lets go of what has left.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "accuracy_fixture.h"
#include "movseg/segmenter.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

SynthOptions clip(SynthCamera camera, bool hard) {
  SynthOptions options;
  options.camera = camera;
  options.frames = 30;
  options.seed = 5;
  if (hard) {  // scripts/synth_sets.sh's camo-* sets
    options.camouflage = true;
    options.object_speed_min = 1;
    options.object_speed_max = 3.5;
    options.noise_sigma = 2;
    options.illumination_drift = 0.1;
  }
  return options;
}

class DenseAccuracy : public ::testing::TestWithParam<SynthCamera> {};

TEST_P(DenseAccuracy, MeanIouAbove085OnPlainAnd070OnCamouflagedObjects) {
  EXPECT_GE(test::meanIou(clip(GetParam(), false), test::withMethod(Method::kDense)), 0.85);
  EXPECT_GE(test::meanIou(clip(GetParam(), true), test::withMethod(Method::kDense)), 0.70);
}

INSTANTIATE_TEST_SUITE_P(EveryCamera, DenseAccuracy,
                         ::testing::Values(SynthCamera::kPan, SynthCamera::kZoom,
                                           SynthCamera::kRotate, SynthCamera::kShake,
                                           SynthCamera::kStatic, SynthCamera::kMix),
                         [](const ::testing::TestParamInfo<SynthCamera>& param_info) {
                           return synthCameraName(param_info.param);
                         });

TEST(Dense, MasksOfTheFirstFramesDoNotDependOnLaterOnes) {
  const SynthSequence sequence(clip(SynthCamera::kMix, true));
  Segmenter whole(test::withMethod(Method::kDense)), stopped(test::withMethod(Method::kDense));
  std::vector<cv::Mat> whole_masks, stopped_masks;
  for (int t = 0; t < sequence.size(); ++t) {
    whole_masks.push_back(whole.process(sequence.frame(t).frame).mask);
    if (t < 12) stopped_masks.push_back(stopped.process(sequence.frame(t).frame).mask);
  }
  whole_masks.resize(stopped_masks.size());
  ASSERT_GT(cv::countNonZero(stopped_masks.back()), 0);
  EXPECT_TRUE(test::identical(whole_masks, stopped_masks));
}

// A textured square crosses a still textured scene and leaves it on the right: once it is
// gone, nothing in the frame moves, and the memory of it must fade within a few frames.
TEST(Dense, AMoverThatLeavesTheViewLeavesTheMask) {
  const cv::Mat scene = test::texture({160, 120}, 3);
  const cv::Mat object = test::texture({30, 30}, 4);
  Segmenter segmenter(test::withMethod(Method::kDense));
  int gone_at = -1;
  for (int t = 0; t < 40; ++t) {
    cv::Mat frame = scene.clone();
    const int x = 60 + 5 * t;
    const cv::Rect inside = cv::Rect(x, 45, 30, 30) & cv::Rect({0, 0}, frame.size());
    if (!inside.empty()) {
      object(cv::Rect({0, 0}, inside.size())).copyTo(frame(inside));
    } else if (gone_at < 0) {
      gone_at = t;
    }
    const int found = cv::countNonZero(segmenter.process(frame).mask);
    if (t == 8) {
      EXPECT_GT(found, 400) << "the moving square is found";
    }
    if (gone_at >= 0 && t >= gone_at + 3) {
      EXPECT_EQ(found, 0) << "frame " << t;
    }
  }
  EXPECT_GT(gone_at, 0);
}

}  // namespace
}  // namespace movseg
