// §3.1: the camera model is recovered from tracked features despite a moving object and noise.
#include <gtest/gtest.h>

#include "core/frame.h"
#include "motion/compensation.h"
#include "motion/motion_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

using test::cornerError;
using test::makePair;
using test::PairSpec;
using test::similarityAboutCentre;

// The frame as §3.1 sees it, at the alignment scale.
AlignmentFrame aligned(const cv::Mat& bgr, const Params& params) {
  return prepareAlignment(prepareFrame(bgr, params).small_grey, params);
}

MotionEstimate estimate(const test::FramePair& pair, const Params& params) {
  return estimateCameraMotion(aligned(pair.prev, params), aligned(pair.cur, params),
                              cv::Matx33d::eye(), params, 42);
}

struct KnownAffine {
  const char* name;
  double degrees, scale;
  cv::Point2d shift;
  double shear;
};

class RecoversKnownAffine : public ::testing::TestWithParam<KnownAffine> {};

TEST_P(RecoversKnownAffine, CornersWithinHalfPixelWithObjectAndNoise) {
  const KnownAffine& a = GetParam();
  PairSpec spec;
  spec.camera = similarityAboutCentre(spec.size, a.degrees, a.scale, a.shift, a.shear);
  spec.object_fraction = 0.30;
  spec.noise_sigma = 2.0;
  const MotionEstimate motion = estimate(makePair(spec), Params());
  ASSERT_FALSE(motion.fallback);
  EXPECT_LT(cornerError(motion.model, spec.camera, spec.size), 0.5) << a.name;
  EXPECT_GT(motion.matches.size(), 40u);
}

INSTANTIATE_TEST_SUITE_P(
    Motion, RecoversKnownAffine,
    ::testing::Values(KnownAffine{"translation", 0, 1, {4.5, -3.2}, 0},
                      KnownAffine{"rotation 5 deg", 5, 1, {1, 0}, 0},
                      KnownAffine{"rotation -3 deg", -3, 1, {0, 2}, 0},
                      KnownAffine{"zoom in 1.1", 0, 1.1, {0, 0}, 0},
                      KnownAffine{"zoom out 0.9", 1, 0.9, {2, 1}, 0},
                      KnownAffine{"shear", 0, 1, {1, 1}, 0.03}),
    [](const ::testing::TestParamInfo<KnownAffine>& param_info) {
      std::string name = param_info.param.name;
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(Motion, RecoversHomographyWithHomographyModel) {
  PairSpec spec;
  spec.camera = similarityAboutCentre(spec.size, 2, 1.02, {2, -1});
  spec.camera(2, 0) = 1e-4;  // mild perspective
  spec.camera(2, 1) = -5e-5;
  spec.object_fraction = 0.15;
  Params params;
  params.motion_model = MotionModel::kHomography;
  const MotionEstimate motion = estimate(makePair(spec), params);
  ASSERT_FALSE(motion.fallback);
  EXPECT_LT(cornerError(motion.model, spec.camera, spec.size), 0.5);
}

TEST(Motion, ModelIsScaledBackFromTheAlignmentScale) {
  PairSpec spec;
  spec.size = cv::Size(640, 480);
  spec.camera = similarityAboutCentre(spec.size, 2, 1.03, {6, -4});
  spec.object_fraction = 0.2;
  Params params;  // alignment at width 320: half scale
  const test::FramePair pair = makePair(spec);
  ASSERT_DOUBLE_EQ(prepareFrame(pair.cur, params).align_scale, 0.5);
  const MotionEstimate motion = estimateCameraMotion(
      aligned(pair.prev, params), aligned(pair.cur, params), cv::Matx33d::eye(), params, 1);
  const cv::Matx33d full = cv::Matx33d(2, 0, 0, 0, 2, 0, 0, 0, 1) * motion.model *
                           cv::Matx33d(0.5, 0, 0, 0, 0.5, 0, 0, 0, 1);
  EXPECT_LT(cornerError(full, spec.camera, spec.size), 1.0);  // 0.5 px at the alignment scale
}

// The outer layer exists for a large object whose motion is close to the camera's: its points
// fall inside RANSAC's inlier distance and bias the least-squares fit, until the frame
// difference moves them to S_f. (A tolerant inlier distance, as on blurry video, makes the
// case common.)
TEST(Motion, TwoLayerIterationBeatsSingleRansacPassOnCoherentObject) {
  double single_total = 0, two_layer_total = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    PairSpec spec;
    spec.seed = seed;
    spec.camera = similarityAboutCentre(spec.size, 1, 1.0, {3, 1});
    spec.object_fraction = 0.40;
    spec.object_motion = {4.6, 2.4};  // 2 px from the camera's (3, 1) near the object
    const test::FramePair pair = makePair(spec);
    Params two_layer;
    two_layer.ransac_threshold = 3.0;
    Params single = two_layer;
    single.max_outer_iterations = 1;
    single_total += cornerError(estimate(pair, single).model, spec.camera, spec.size);
    two_layer_total += cornerError(estimate(pair, two_layer).model, spec.camera, spec.size);
  }
  EXPECT_LT(two_layer_total, 0.7 * single_total)
      << "single pass " << single_total / 5 << " px, two-layer " << two_layer_total / 5 << " px";
}

TEST(Motion, IsDeterministicForAFixedSeed) {
  PairSpec spec;
  spec.camera = similarityAboutCentre(spec.size, 2, 1.0, {2, 2});
  spec.object_fraction = 0.2;
  const test::FramePair pair = makePair(spec);
  const MotionEstimate a = estimate(pair, Params());
  const MotionEstimate b = estimate(pair, Params());
  EXPECT_EQ(cv::norm(cv::Mat(a.model), cv::Mat(b.model), cv::NORM_INF), 0.0);
  EXPECT_EQ(a.background, b.background);
  // The same fit twice, and a fit of the camera (not an identity fallback returned twice).
  EXPECT_FALSE(a.fallback);
  EXPECT_LT(cornerError(a.model, spec.camera, spec.size), 0.5);
}

TEST(Motion, TexturelessPairFallsBackToWarmModel) {
  const cv::Mat flat(240, 320, CV_8UC3, cv::Scalar(90, 90, 90));
  const Params params;
  const cv::Matx33d warm(1, 0, 2, 0, 1, 1, 0, 0, 1);
  const MotionEstimate motion =
      estimateCameraMotion(aligned(flat, params), aligned(flat, params), warm, params, 0);
  EXPECT_TRUE(motion.fallback);
  EXPECT_EQ(motion.model, warm);
}

TEST(Motion, CompensatedDifferenceIsZeroOnPerfectAlignment) {
  PairSpec spec;
  spec.camera = similarityAboutCentre(spec.size, 0, 1.0, {5, 0});
  spec.noise_sigma = 0;
  const test::FramePair pair = makePair(spec);
  const cv::Mat d = compensatedDifference(pair.prev, pair.cur, spec.camera);
  ASSERT_EQ(d.type(), CV_32F);
  // Interpolation of an integer shift is exact, and the uncovered strip is 0 (eq. 4 counts
  // only what the previous frame covers): zero everywhere.
  EXPECT_EQ(cv::countNonZero(d), 0);
  // Unaligned, the same texture differs by about 47 levels a pixel (mean squared 2232).
  const cv::Mat unaligned = compensatedDifference(pair.prev, pair.cur, cv::Matx33d::eye());
  EXPECT_GT(cv::mean(unaligned)[0], 1000.0);
}

}  // namespace
}  // namespace movseg
