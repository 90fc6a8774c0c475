// End to end on the synthetic generator: for every camera motion the paper's method finds the
// moving objects (mean IoU over a short clip; README's table has the long runs).
#include <gtest/gtest.h>

#include "accuracy_fixture.h"

namespace movseg {
namespace {

double meanIou(SynthCamera camera, cv::Size size) {
  SynthOptions clip;
  clip.camera = camera;
  clip.size = size;
  clip.frames = 25;
  clip.seed = 11;
  Params params;
  params.method = Method::kPaper;
  return test::meanIou(clip, params);
}

class SyntheticAccuracy : public ::testing::TestWithParam<SynthCamera> {};

// Measured 0.964 (the lowest camera) to 0.988.
TEST_P(SyntheticAccuracy, MeanIouAbove095At320x240) {
  EXPECT_GE(meanIou(GetParam(), {320, 240}), 0.95) << synthCameraName(GetParam());
}

INSTANTIATE_TEST_SUITE_P(EveryCamera, SyntheticAccuracy,
                         ::testing::Values(SynthCamera::kPan, SynthCamera::kZoom,
                                           SynthCamera::kRotate, SynthCamera::kShake,
                                           SynthCamera::kStatic, SynthCamera::kMix),
                         [](const ::testing::TestParamInfo<SynthCamera>& param_info) {
                           return synthCameraName(param_info.param);
                         });

// Measured 0.909: at twice the size the objects' speeds double as well.
TEST(SyntheticAccuracy, MeanIouAbove089At640x480) {
  EXPECT_GE(meanIou(SynthCamera::kMix, {640, 480}), 0.89);
}

}  // namespace
}  // namespace movseg
