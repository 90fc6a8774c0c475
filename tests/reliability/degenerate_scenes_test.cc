// Scenes no camera should produce but every camera does: each gives a valid mask, an honest
// diagnostic and no exception (docs/reliability.md).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "movseg/fields.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

const cv::Size kSize(320, 240);

// A threshold far above the floor means the alignment's residual at the background matches
// was large: the pair could not be aligned, and eq. (3) stopped trusting the difference.
// These scenes exercise the paper's fallbacks (identity model, raised lambda); the contract
// tests hold every method to valid masks on such frames.
Params paper() { return test::withMethod(Method::kPaper); }

bool lambdaRaised(const Result& r) { return r.diagnostics.lambda > 10 * Params().lambda; }

TEST(DegenerateScenes, FlatFramesFallBackToTheIdentityWithAnEmptyMask) {
  for (const double level : {0.0, 90.0, 255.0}) {
    Segmenter segmenter(paper());
    const cv::Mat flat(kSize, CV_8UC3, cv::Scalar::all(level));
    EXPECT_TRUE(segmenter.process(flat).diagnostics.first_frame);
    for (int i = 0; i < 2; ++i) {
      const Result r = segmenter.process(flat);
      test::expectValidResult(r, kSize);
      EXPECT_EQ(r.diagnostics.features, 0) << level;
      EXPECT_TRUE(r.diagnostics.motion_fallback) << level;
      EXPECT_EQ(r.diagnostics.model, cv::Matx33d::eye()) << level;
      EXPECT_EQ(cv::countNonZero(r.mask), 0) << level;
    }
  }
}

// README, "Bad input": every method that measures the camera flags a flat frame pair, which
// shows no camera motion to measure (motion_fallback); MOG2, which measures none, flags nothing.
TEST(DegenerateScenes, FlatFramesAreFlaggedByEveryMethodThatMeasuresTheCamera) {
  const cv::Mat flat(kSize, CV_8UC3, cv::Scalar::all(90));
  for (const Method method : {Method::kPaper, Method::kDiff, Method::kMog2,
                              Method::kMog2Compensated, Method::kDense}) {
    Segmenter segmenter(test::withMethod(method));
    segmenter.process(flat);
    segmenter.process(flat);  // `dense` takes the second showing for a repeated frame
    const Result r = segmenter.process(flat);
    test::expectValidResult(r, kSize);
    EXPECT_EQ(r.diagnostics.motion_fallback, method != Method::kMog2) << static_cast<int>(method);
  }
}

// `dense` measures the camera from the flow of textured samples: a flat frame has none, a frame
// under 16 pixels a side no flow at all. Either way the pair says so (README, "Bad input").
TEST(DegenerateScenes, DenseFlagsFramesWithoutMeasurableMotion) {
  const std::vector<cv::Mat> frames{cv::Mat(kSize, CV_8UC3, cv::Scalar::all(0)),
                                    cv::Mat(kSize, CV_8UC3, cv::Scalar::all(90)),
                                    cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(90)),
                                    cv::Mat(1000, 7, CV_8UC3, cv::Scalar::all(90))};
  for (const cv::Mat& frame : frames) {
    Segmenter segmenter(test::withMethod(Method::kDense));
    EXPECT_FALSE(segmenter.process(frame).diagnostics.motion_fallback);  // a first frame
    // Shown again, the frame is a repeat (docs/design.md, "Repeated frames"); from the third
    // time on, a still scene, measured.
    EXPECT_TRUE(segmenter.process(frame).diagnostics.repeated_frame) << frame.size;
    for (int i = 0; i < 2; ++i) {
      const Result r = segmenter.process(frame);
      test::expectValidResult(r, frame.size());
      EXPECT_TRUE(r.diagnostics.motion_fallback) << frame.size;
      EXPECT_EQ(r.diagnostics.model, cv::Matx33d::eye()) << frame.size;
      EXPECT_EQ(cv::countNonZero(r.mask), 0) << frame.size;
    }
  }
  // A textured frame is measured: the flag is not raised for nothing.
  Segmenter segmenter(test::withMethod(Method::kDense));
  segmenter.process(test::texture(kSize, 5));
  segmenter.process(test::texture(kSize, 5));  // a repeat
  const Result still = segmenter.process(test::texture(kSize, 5));
  EXPECT_FALSE(still.diagnostics.repeated_frame);
  EXPECT_FALSE(still.diagnostics.motion_fallback);
}

TEST(DegenerateScenes, PureNoiseRaisesLambdaInsteadOfLightingUp) {
  Segmenter segmenter(paper());
  for (int i = 0; i < 3; ++i) {
    cv::Mat noise(kSize, CV_8UC3);
    cv::RNG(i + 1).fill(noise, cv::RNG::UNIFORM, 0, 256);
    const Result r = segmenter.process(noise);
    test::expectValidResult(r, kSize);
    if (i == 0) continue;
    EXPECT_TRUE(lambdaRaised(r)) << r.diagnostics.lambda;
    EXPECT_LT(test::foregroundShare(r.mask), 0.01);
  }
}

// The methods that align the pair before comparing it flag a scene cut; MOG2 learns the new
// scene by itself (docs/reliability.md).
class SceneCuts : public ::testing::TestWithParam<Method> {
 protected:
  Segmenter segmenter() const {
    Params p;
    p.method = GetParam();
    return Segmenter(p);
  }
};

// Two unrelated pictures: RANSAC still fits some model to chance matches (or to the flow), but
// the pair stays different after alignment: flagged, empty mask; the next pair, the new scene
// seen from two pixels further (not the same frame again, which `dense` would take for a
// repeat and not align), is aligned again.
TEST_P(SceneCuts, SceneCutIsFlaggedWithAnEmptyMaskThenRecovers) {
  const cv::Mat new_scene = test::texture({500, 400}, 2);
  Segmenter segmenter = this->segmenter();
  segmenter.process(test::texture(kSize, 1));
  const Result cut = segmenter.process(test::view(new_scene, {50, 80}, kSize));
  test::expectValidResult(cut, kSize);
  EXPECT_TRUE(cut.diagnostics.scene_cut);
  EXPECT_EQ(cv::countNonZero(cut.mask), 0);

  const Result after = segmenter.process(test::view(new_scene, {52, 81}, kSize));
  test::expectValidResult(after, kSize);
  EXPECT_FALSE(after.diagnostics.repeated_frame);
  EXPECT_FALSE(after.diagnostics.scene_cut);
  EXPECT_FALSE(lambdaRaised(after));
  const cv::Matx33d shift(1, 0, -2, 0, 1, -1, 0, 0, 1);
  EXPECT_LT(test::cornerError(after.diagnostics.model, shift, kSize), 0.5);
  EXPECT_EQ(cv::countNonZero(after.mask), 0);
}

// A 100-pixel jump is beyond the LK pyramid's (and DIS's) reach: the pair is misaligned and
// looks like a scene cut; the next, ordinary pair is aligned again.
TEST_P(SceneCuts, CameraJumpBeyondReachIsFlaggedAsACutThenRecovers) {
  const cv::Mat world = test::texture({700, 400}, 4);
  Segmenter segmenter = this->segmenter();
  segmenter.process(test::view(world, {50, 80}, kSize));
  const Result jump = segmenter.process(test::view(world, {150, 80}, kSize));
  test::expectValidResult(jump, kSize);
  EXPECT_TRUE(jump.diagnostics.scene_cut);
  EXPECT_EQ(cv::countNonZero(jump.mask), 0);

  const Result after = segmenter.process(test::view(world, {152, 81}, kSize));
  test::expectValidResult(after, kSize);
  EXPECT_FALSE(after.diagnostics.scene_cut);
  const cv::Matx33d shift(1, 0, -2, 0, 1, -1, 0, 0, 1);
  EXPECT_LT(test::cornerError(after.diagnostics.model, shift, kSize), 0.5);
  EXPECT_EQ(cv::countNonZero(after.mask), 0);
}

INSTANTIATE_TEST_SUITE_P(AligningMethods, SceneCuts,
                         ::testing::Values(Method::kPaper, Method::kDense, Method::kDiff),
                         [](const ::testing::TestParamInfo<Method>& param_info) {
                           return enumNames<Method>()[static_cast<size_t>(param_info.param)];
                         });

// An object that fills the view moves exactly like a camera would: a moving-camera segmenter
// takes it for camera motion, as it must.
TEST(DegenerateScenes, WholeFrameMovingIsTakenForCameraMotion) {
  const cv::Mat world = test::texture({600, 400}, 3);
  Segmenter segmenter(paper());
  segmenter.process(test::view(world, {100, 80}, kSize));
  for (int i = 1; i < 4; ++i) {
    const Result r = segmenter.process(test::view(world, {100 + 4 * i, 80 + 2 * i}, kSize));
    test::expectValidResult(r, kSize);
    EXPECT_FALSE(r.diagnostics.motion_fallback);
    const cv::Matx33d shift(1, 0, -4, 0, 1, -2, 0, 0, 1);
    EXPECT_LT(test::cornerError(r.diagnostics.model, shift, kSize), 0.5);
    EXPECT_EQ(cv::countNonZero(r.mask), 0);
  }
}

// With --static nothing is aligned: every pixel differs, so lambda rises with the difference
// and the mask stays nearly empty rather than covering the frame.
TEST(DegenerateScenes, WholeFrameMovingBeforeAStaticCameraRaisesLambda) {
  const cv::Mat world = test::texture({600, 400}, 3);
  Params params = paper();
  params.static_camera = true;
  Segmenter segmenter(params);
  segmenter.process(test::view(world, {100, 80}, kSize));
  for (int i = 1; i < 3; ++i) {
    const Result r = segmenter.process(test::view(world, {100 + 4 * i, 80 + 2 * i}, kSize));
    test::expectValidResult(r, kSize);
    EXPECT_EQ(r.diagnostics.model, cv::Matx33d::eye());
    EXPECT_TRUE(lambdaRaised(r)) << r.diagnostics.lambda;
    EXPECT_LT(test::foregroundShare(r.mask), 0.01);
  }
}

// A textured object crosses a panning view, then stops in the world (it keeps moving in the
// image with the background): the two-frame method forgets it at once.
TEST(DegenerateScenes, ObjectThatStopsLeavesTheMask) {
  const cv::Mat world = test::texture({600, 400}, 5);
  const cv::Mat object = test::texture({60, 60}, 6);
  const int stop = 6;
  Segmenter segmenter(paper());
  for (int i = 0; i < stop + 4; ++i) {
    const int camera_x = 100 + 3 * i;
    const int object_x = 200 + 5 * std::min(i, stop - 1);  // in the world
    cv::Mat frame = test::view(world, {camera_x, 80}, kSize);
    object.copyTo(frame(cv::Rect(object_x - camera_x, 90, 60, 60)));
    const Result r = segmenter.process(frame);
    test::expectValidResult(r, kSize);
    if (i == 0) continue;
    if (i < stop) {
      EXPECT_GT(test::foregroundShare(r.mask), 0.03) << "frame " << i;
    } else {
      EXPECT_LT(test::foregroundShare(r.mask), 0.005) << "frame " << i;
      EXPECT_EQ(r.diagnostics.foreground_seeds, 0) << "frame " << i;
    }
  }
}

// An overlay video of frames under 16 pixels a side is enlarged by a whole factor (FFmpeg's
// scaler wrote past its buffers for a 4x4 Motion JPEG .avi: the run aborted).
TEST(DegenerateScenes, TinyFramesMakeAnOverlayVideoToo) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "frames");
  for (int i = 0; i < 3; ++i) {
    cv::imwrite(dir / ("frames/0000" + std::to_string(i) + ".png"), test::texture({4, 4}, i + 1));
  }
  for (const char* video : {"o.avi", "o.mp4"}) {
    const auto run = test::runCli("segment " + (dir / "frames") + " -o " + (dir / video) +
                                  "_masks --overlay " + (dir / video) + " -q");
    ASSERT_EQ(run.exit_code, 0) << video << run.output;
    cv::VideoCapture played(dir / video);
    int frames = 0;
    for (cv::Mat frame; played.read(frame); ++frames) EXPECT_EQ(frame.size(), cv::Size(16, 16));
    EXPECT_EQ(frames, 3) << video;
  }
}

TEST(DegenerateScenes, OneFrameVideoThroughTheCliGivesOneEmptyMask) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "frames");
  cv::imwrite(dir / "frames/00000.png", test::texture(kSize, 7));
  const auto run = test::runCli("segment " + (dir / "frames") + " -o " + (dir / "out") +
                                " --stats " + (dir / "stats.jsonl") + " -q");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, "");
  EXPECT_EQ(test::filesIn(dir / "out"), (std::vector<std::string>{"00000.png", "movseg-run.json"}));
  const cv::Mat mask = cv::imread(dir / "out/00000.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(mask.size(), kSize);
  EXPECT_EQ(cv::countNonZero(mask), 0);
  std::ifstream stats(dir / "stats.jsonl");
  std::string line, extra;
  ASSERT_TRUE(std::getline(stats, line));
  EXPECT_FALSE(std::getline(stats, extra));
  EXPECT_TRUE(nlohmann::json::parse(line).at("first_frame").get<bool>());
}

}  // namespace
}  // namespace movseg
