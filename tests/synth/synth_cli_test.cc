#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "synth/synth.h"
#include "test_support.h"

namespace movseg {
namespace {

using test::runCli;
using test::TempDir;

TEST(SynthCli, WritesFramesMasksAndCameraModels) {
  TempDir dir;
  const std::string out = dir / "clip";
  const auto result =
      runCli("synth -o " + out + " --frames 5 --size 64x48 --seed 3 --camera pan --objects 1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output,
            "synth: wrote 5 frames (64x48, camera pan, 1 object, seed 3) to " + out + "\n");

  SynthOptions options;
  options.frames = 5;
  options.size = cv::Size(64, 48);
  options.seed = 3;
  options.camera = SynthCamera::kPan;
  options.objects = 1;
  const SynthSequence sequence(options);
  for (int t = 0; t < 5; ++t) {
    const std::string name = "0000" + std::to_string(t) + ".png";
    const SynthFrame expected = sequence.frame(t);
    const cv::Mat frame = cv::imread(out + "/frames/" + name, cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(out + "/masks/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(frame.empty()) << name;
    ASSERT_FALSE(mask.empty()) << name;
    EXPECT_EQ(cv::norm(frame, expected.frame, cv::NORM_INF), 0) << name;
    EXPECT_EQ(cv::norm(mask, expected.mask, cv::NORM_INF), 0) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(out + "/frames/00005.png"));

  std::ifstream cameras(out + "/camera.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(cameras, line)) {
    ++lines;
    const nlohmann::json entry = nlohmann::json::parse(line);
    ASSERT_EQ(entry.at("frame").get<int>(), lines);
    const auto& model = entry.at("model");
    ASSERT_EQ(model.size(), 3u);
    const cv::Matx33d expected = sequence.frame(lines).camera;
    for (int r = 0; r < 3; ++r) {
      ASSERT_EQ(model[r].size(), 3u);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(model[r][c].get<double>(), expected(r, c));
    }
  }
  EXPECT_EQ(lines, 4);
  EXPECT_FALSE(std::filesystem::exists(out + "/poses.jsonl"));
}

TEST(SynthCli, DepthSceneAlsoWritesThePoses) {
  TempDir dir;
  const std::string out = dir / "clip";
  const auto result = runCli("synth -o " + out +
                             " --scene depth --camera dolly --frames 3 --size 96x72 --seed 2 "
                             "--objects 1 --camouflage --object-speed 1-3.5 --noise 2 "
                             "--illumination 0.1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output, "synth: wrote 3 frames (96x72, scene depth, camera dolly, 1 object, "
                           "seed 2) to " + out + "\n");
  SynthOptions options;
  options.frames = 3;
  options.size = cv::Size(96, 72);
  options.seed = 2;
  options.scene = SynthScene::kDepth;
  options.camera = SynthCamera::kDolly;
  options.objects = 1;
  options.camouflage = true;
  options.object_speed_max = 3.5;
  options.noise_sigma = 2;
  options.illumination_drift = 0.1;
  const SynthSequence sequence(options);
  EXPECT_EQ(cv::norm(cv::imread(out + "/frames/00002.png"), sequence.frame(2).frame, cv::NORM_INF),
            0);
  std::ifstream poses(out + "/poses.jsonl");
  std::string line;
  int t = 0;
  for (; std::getline(poses, line); ++t) {
    const nlohmann::json entry = nlohmann::json::parse(line);
    ASSERT_EQ(entry.at("frame").get<int>(), t);
    const SynthPinhole pose = *sequence.frame(t).pose;
    for (int r = 0; r < 3; ++r) {
      EXPECT_EQ(entry.at("centre")[r].get<double>(), pose.centre[r]);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(entry.at("K")[r][c].get<double>(), pose.intrinsics(r, c));
        EXPECT_EQ(entry.at("R")[r][c].get<double>(), pose.rotation(r, c));
      }
    }
  }
  EXPECT_EQ(t, 3);
}

TEST(SynthCli, BadOptionsFailWithOneLine) {
  TempDir dir;
  const std::string out = dir / "clip";
  for (const std::string bad :
       {"--size 10x10", "--size abc", "--objects 0", "--objects 4", "--frames 0", "--camera tilt",
        "--seed -1", "--seed 18446744073709551616", "--seed 1x", "--object-speed 3-1", "--object-speed 0-2", "--object-speed 40",
        "--object-speed fast", "--object-speed -1-2", "--noise -1", "--illumination 0.6",
        "--scene cube", "--camera dolly", "--scene plane --camera forward",
        "--scene depth --camera tilt"}) {
    const auto result = runCli("synth -o " + out + " " + bad);
    EXPECT_EQ(result.exit_code, test::kExitUsage) << bad << ": " << result.output;
    EXPECT_EQ(result.output.rfind("movseg: error: ", 0), 0u) << bad << ": " << result.output;
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << bad << ": " << result.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad << ": wrote files anyway";
  }
  EXPECT_EQ(runCli("synth -o " + dir / "plus" + " --frames 2 --size 64x48 --seed +5").exit_code,
            0);  // as CLI11 reads every other number
  const auto no_output = runCli("synth --frames 3");
  EXPECT_EQ(no_output.exit_code, test::kExitUsage);
  EXPECT_EQ(no_output.output.rfind("movseg: error: ", 0), 0u) << no_output.output;
}

}  // namespace
}  // namespace movseg
