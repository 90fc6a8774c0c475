// End to end on the synthetic generator: for every camera motion the paper's method finds the
// moving objects (mean IoU over a short clip; README's table has the long runs).
#include <gtest/gtest.h>

#include "movseg/segmenter.h"
#include "synth/synth.h"

namespace movseg {
namespace {

double meanIou(SynthCamera camera, cv::Size size) {
  SynthOptions options;
  options.camera = camera;
  options.size = size;
  options.frames = 25;
  options.seed = 11;
  const SynthSequence sequence(options);
  Segmenter segmenter;
  double sum = 0;
  int counted = 0;
  for (int t = 0; t < sequence.size(); ++t) {
    const SynthFrame f = sequence.frame(t);
    const cv::Mat mask = segmenter.process(f.frame).mask;
    if (t == 0) continue;  // no previous frame, no motion
    const double uni = cv::countNonZero(mask | f.mask);
    sum += uni > 0 ? cv::countNonZero(mask & f.mask) / uni : 1.0;
    ++counted;
  }
  return sum / counted;
}

class SyntheticAccuracy : public ::testing::TestWithParam<SynthCamera> {};

TEST_P(SyntheticAccuracy, MeanIouAbove080At320x240) {
  EXPECT_GE(meanIou(GetParam(), {320, 240}), 0.80) << synthCameraName(GetParam());
}

INSTANTIATE_TEST_SUITE_P(EveryCamera, SyntheticAccuracy,
                         ::testing::Values(SynthCamera::kPan, SynthCamera::kZoom,
                                           SynthCamera::kRotate, SynthCamera::kShake,
                                           SynthCamera::kStatic, SynthCamera::kMix),
                         [](const ::testing::TestParamInfo<SynthCamera>& param_info) {
                           return synthCameraName(param_info.param);
                         });

TEST(SyntheticAccuracy, MeanIouAbove080At640x480) {
  EXPECT_GE(meanIou(SynthCamera::kMix, {640, 480}), 0.80);
}

}  // namespace
}  // namespace movseg
