// `movseg segment` end to end: outputs, and every kind of bad input of the foundation issue
// gives a one-line message and a non-zero exit.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/metrics.h"
#include "movseg/fields.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

namespace fs = std::filesystem;

std::string synthClip(const test::TempDir& dir, int frames) {
  EXPECT_EQ(test::runCli("synth -o " + dir / "clip" + " --frames " + std::to_string(frames))
                .exit_code, 0);
  return dir / "clip/frames";
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The same files in `a` and `b` (`count` entries, folders among them), byte for byte, folders
// compared the same way.
void expectSameFiles(const std::string& a, const std::string& b, size_t count) {
  const std::vector<std::string> files = test::filesIn(a);
  ASSERT_EQ(files.size(), count) << a;
  EXPECT_EQ(files, test::filesIn(b));
  for (const std::string& name : files) {
    const std::string in_a = a + "/" + name, in_b = b + "/" + name;
    if (fs::is_directory(in_a)) {
      expectSameFiles(in_a, in_b, test::filesIn(in_a).size());
      continue;
    }
    EXPECT_EQ(bytesOf(in_a), bytesOf(in_b)) << in_b;
  }
}

TEST(SegmentCli, WritesOneMaskPerFrameAndStatsLines) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 6);
  const test::CommandResult r = test::runCli("segment " + frames + " -o " + dir / "out" +
                                             " --stats " + dir / "stats.jsonl" + " --overlay");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("segment: 6 frames"), std::string::npos) << r.output;
  for (int i = 0; i < 6; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%05d.png", i);
    const cv::Mat mask = cv::imread(dir / "out/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_8UC1) << name;
    EXPECT_EQ(mask.size(), cv::Size(320, 240));
    EXPECT_EQ(cv::countNonZero((mask != 0) & (mask != 255)), 0);
    EXPECT_TRUE(fs::exists(dir / "out/overlay/" + name));
    if (i < 2) continue;  // the movers are found from the second pair on
    EXPECT_GT(scoreFrame(mask, cv::imread(dir / "clip/masks/" + name, cv::IMREAD_GRAYSCALE)).j, 0.8)
        << name;
  }
  std::ifstream stats(dir / "stats.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(stats, line)) {
    const nlohmann::json j = nlohmann::json::parse(line);
    EXPECT_EQ(j.at("frame").get<int>(), lines);
    EXPECT_EQ(j.at("model").size(), 3u);  // 3 rows of 3
    EXPECT_EQ(j.at("model")[0].size(), 3u);
    for (const FieldInfo& field : diagnosticFields()) EXPECT_TRUE(j.contains(field.name)) << field.name;
    EXPECT_EQ(j.size(), diagnosticFields().size() + 2);  // and "frame", "decode_errors"
    EXPECT_EQ(j.at("decode_errors").get<int>(), 0);
    EXPECT_GT(j.at("total_ms").get<double>(), 0.0);
    EXPECT_EQ(j.at("first_frame").get<bool>(), lines == 0);
    ++lines;
  }
  EXPECT_EQ(lines, 6);
}

TEST(SegmentCli, DebugWritesEachStagesPictures) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 3);
  ASSERT_EQ(test::runCli("segment " + frames + " -o " + dir / "paper" + " --method paper --debug -q")
                .exit_code, 0);
  for (const char* stage : {"matches", "difference", "features", "features_refined", "mask"}) {
    EXPECT_TRUE(fs::exists(dir / "paper/debug/" + stage + "/00002.png")) << stage;
  }
  // dense, on 640x480 frames: its stages at the working scale, the edges and mask at the input's.
  const std::string large = dir / "large";
  ASSERT_EQ(test::runCli("synth -o " + large + " --frames 3 --size 640x480").exit_code, 0);
  ASSERT_EQ(
      test::runCli("segment " + large + "/frames -o " + dir / "dense" + " --debug -q").exit_code,
      0);
  const std::vector<std::pair<std::string, cv::Size>> stages{
      {"residual", {320, 240}}, {"carried", {320, 240}}, {"confirmation", {320, 240}},
      {"uncovered", {320, 240}}, {"unary", {320, 240}}, {"regions", {320, 240}},
      {"edges", {640, 480}},
      {"mask", {640, 480}}};
  for (const auto& [stage, size] : stages) {
    const cv::Mat picture = cv::imread(dir / "dense/debug/" + stage + "/00002.png");
    EXPECT_EQ(picture.size(), size) << stage;
  }
}

TEST(SegmentCli, MissingInput) {
  const test::TempDir dir;
  test::expectOneLineError(test::runCli("segment " + dir / "nothing.mp4" + " -o " + dir / "out"),
                     "nothing.mp4", test::kExitRunFailed);
}

TEST(SegmentCli, EmptyAndUnreadableVideos) {
  const test::TempDir dir;
  { std::ofstream(dir / "empty.mp4"); }
  { std::ofstream(dir / "junk.mp4") << "this is not a video at all"; }
  for (const char* name : {"empty.mp4", "junk.mp4"}) {
    const test::CommandResult r = test::runCli("segment " + dir / name + " -o " + dir / "out");
    test::expectOneLineError(r, name, test::kExitRunFailed);
    EXPECT_FALSE(fs::exists(dir / "out/00000.png"));
  }
}

TEST(SegmentCli, FolderWithoutImages) {
  const test::TempDir dir;
  fs::create_directories(dir / "frames");
  { std::ofstream(dir / "frames/readme.txt") << "no images here"; }
  test::expectOneLineError(test::runCli("segment " + dir / "frames" + " -o " + dir / "out"),
                     "no images", test::kExitRunFailed);
}

TEST(SegmentCli, CorruptImageInAFolderIsNamed) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 3);
  { std::ofstream(frames + "/00001.png", std::ios::trunc) << "garbage"; }
  test::expectOneLineError(test::runCli("segment " + frames + " -o " + dir / "out"), "00001.png",
                           test::kExitRunFailed);
  EXPECT_TRUE(fs::exists(dir / "out/00000.png"));  // what came before is complete
  EXPECT_FALSE(fs::exists(dir / "out/00001.png"));
}

// --ignore: white (above 127) where nothing moves, 127 and below (a JPEG's near-black ringing)
// not ignored, the image scaled to the frames; the manifest records it. An image that cannot be
// read stops the run before anything is written.
TEST(SegmentCli, IgnoreLeavesARegionOutOfEveryMask) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 6);
  ASSERT_EQ(test::runCli("segment " + frames + " -o " + dir / "plain").exit_code, 0);
  cv::Mat region(120, 160, CV_8U, cv::Scalar(127));  // half the frames' size: scaled
  region(cv::Rect(0, 0, 80, 120)).setTo(128);
  const cv::Rect left(0, 0, 160, 240);  // in the frames
  ASSERT_TRUE(cv::imwrite(dir / "region.png", region));
  const test::CommandResult r =
      test::runCli("segment " + frames + " -o " + dir / "out" + " --ignore " + dir / "region.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int before = 0, after = 0;
  for (const std::string& name : test::filesIn(dir / "out")) {
    if (name.find(".png") == std::string::npos) continue;
    const cv::Mat mask = cv::imread(dir / "out/" + name, cv::IMREAD_GRAYSCALE);
    const cv::Mat plain = cv::imread(dir / "plain/" + name, cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::countNonZero(mask(left)), 0) << name;
    before += cv::countNonZero(plain(left));
    after += cv::countNonZero(mask);
  }
  EXPECT_GT(before, 0);  // the region held movers
  EXPECT_GT(after, 0);   // and the rest of the frame is still segmented
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(dir / "out/movseg-run.json"));
  EXPECT_EQ(manifest.at("settings").at("ignore"), dir / "region.png");

  test::expectOneLineError(
      test::runCli("segment " + frames + " -o " + dir / "none" + " --ignore " + dir / "no.png"),
      "no.png", test::kExitRunFailed);
  EXPECT_FALSE(fs::exists(dir / "none"));
}

// An --ignore image whose header claims more pixels than OpenCV decodes is refused as such a
// frame is, in our words rather than OpenCV's exception text.
TEST(SegmentCli, IgnoreImageWithAHugeHeaderIsACleanDecodeError) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 2);
  std::ofstream(dir / "huge.pgm", std::ios::binary) << "P5\n2000000 1\n255\n"
                                                    << std::string(16, '\x7f');
  const test::CommandResult r =
      test::runCli("segment " + frames + " -o " + dir / "out" + " --ignore " + dir / "huge.pgm");
  test::expectOneLineError(r, "cannot decode image '" + dir / "huge.pgm" + "'",
                           test::kExitRunFailed);
  EXPECT_EQ(r.output.find("OpenCV"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out/00000.png"));
}

TEST(SegmentCli, UnwritableOutputFolder) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 2);
  { std::ofstream(dir / "a-file") << "x"; }
  test::expectOneLineError(test::runCli("segment " + frames + " -o " + dir / "a-file/out"),
                           "a-file", test::kExitRunFailed);
}

// Grey, BGRA and 16-bit images are converted; a frame of another size restarts the segmenter.
// BGRA and 16-bit frames hold the BGR picture exactly, so their masks are the BGR run's.
TEST(SegmentCli, MixedFrameTypesAndSizesAreAccepted) {
  const test::TempDir dir;
  fs::create_directories(dir / "mixed");
  const std::string clip = synthClip(dir, 4);
  const auto frame = [&](int i) { return cv::imread(clip + "/0000" + std::to_string(i) + ".png"); };
  cv::Mat bgra, deep, grey, small;
  cv::cvtColor(frame(1), bgra, cv::COLOR_BGR2BGRA);
  frame(2).convertTo(deep, CV_16UC3, 256);
  cv::cvtColor(frame(3), grey, cv::COLOR_BGR2GRAY);
  cv::resize(frame(3), small, {160, 120});
  cv::imwrite(dir / "mixed/0.png", frame(0));
  cv::imwrite(dir / "mixed/1.png", bgra);
  cv::imwrite(dir / "mixed/2.png", deep);
  cv::imwrite(dir / "mixed/3.png", grey);
  cv::imwrite(dir / "mixed/4.png", small);
  const test::CommandResult r = test::runCli("segment " + dir / "mixed" + " -o " + dir / "out" +
                                             " --stats " + dir / "s.jsonl");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(test::runCli("segment " + clip + " -o " + dir / "bgr").exit_code, 0);
  EXPECT_NE(r.output.find("1 size resets"), std::string::npos) << r.output;
  EXPECT_EQ(cv::imread(dir / "out/00004.png", cv::IMREAD_UNCHANGED).size(), cv::Size(160, 120));
  const auto mask = [&](const std::string& run, const char* name) {
    return cv::imread(dir / (run + "/" + name), cv::IMREAD_UNCHANGED);
  };
  for (const char* name : {"00001.png", "00002.png"}) {
    ASSERT_EQ(mask("out", name).type(), CV_8UC1) << name;
    EXPECT_GT(cv::countNonZero(mask("bgr", name)), 0) << name;
    EXPECT_EQ(cv::norm(mask("out", name), mask("bgr", name), cv::NORM_INF), 0) << name;
  }
  // The grey frame, converted, still shows the mover.
  const cv::Mat from_grey = mask("out", "00003.png");
  ASSERT_EQ(from_grey.type(), CV_8UC1);
  EXPECT_EQ(from_grey.size(), cv::Size(320, 240));
  EXPECT_EQ(cv::countNonZero((from_grey != 0) & (from_grey != 255)), 0);
  EXPECT_GT(scoreFrame(from_grey, mask("bgr", "00003.png")).j, 0.5);
  std::ifstream stats(dir / "s.jsonl");
  std::vector<bool> resets;
  for (std::string line; std::getline(stats, line);) {
    resets.push_back(nlohmann::json::parse(line).at("reset").get<bool>());
  }
  EXPECT_EQ(resets, (std::vector<bool>{false, false, false, false, true}));
}

// --threads 2 on one input: the next frame is analysed while this one is cut; the same masks
// and debug pictures.
TEST(SegmentCli, TwoThreadsOnOneInputWriteTheOneThreadFiles) {
  const test::TempDir dir;
  const std::string frames = synthClip(dir, 8);
  for (const char* threads : {"1", "2"}) {
    const test::CommandResult r = test::runCli("segment " + frames + " -o " + dir / threads +
                                               " --debug --threads " + threads);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("segment: 8 frames"), std::string::npos) << r.output;
  }
  expectSameFiles(dir / "1", dir / "2", 8 + 2);  // and the run manifest and debug/
  EXPECT_EQ(test::filesIn(dir / "1/debug/unary").size(), 7u);  // from the first pair
}

// Several inputs, N at a time: each input's outputs (--stats and --overlay named in its folder)
// in OUTDIR/<name>/, its masks those of a run of its own.
TEST(SegmentCli, SeveralInputsEachIntoAFolderOfItsOwn) {
  const test::TempDir dir;
  for (const char* name : {"a", "b", "c"}) {
    ASSERT_EQ(test::runCli("synth -o " + dir / name + " --frames 4 --size 160x120").exit_code, 0);
  }
  ASSERT_EQ(test::runCli("segment " + dir / "b/frames" + " -o " + dir / "alone" + " -q").exit_code, 0);
  const test::CommandResult r =
      test::runCli("segment " + dir / "a" + " " + dir / "b/frames" + " " + dir / "c" + " -o " +
                   dir / "out" + " --threads 2 --stats stats.jsonl --overlay");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("segment: 3 of 3 inputs done"), std::string::npos) << r.output;
  for (const std::string& input : {dir / "a", dir / "b/frames", dir / "c"}) {
    EXPECT_NE(r.output.find("segment: " + input + ": 4 frames"), std::string::npos) << r.output;
  }
  for (const char* name : {"a", "b", "c"}) {
    EXPECT_TRUE(fs::exists(dir / "out/" + name + "/stats.jsonl")) << name;
    EXPECT_TRUE(fs::exists(dir / "out/" + name + "/overlay/00003.png")) << name;
    EXPECT_TRUE(fs::exists(dir / "out/" + name + "/movseg-run.json")) << name;
  }
  for (const std::string& mask : test::filesIn(dir / "alone")) {
    if (mask.find(".png") == std::string::npos) continue;  // the manifests name their inputs
    EXPECT_EQ(bytesOf(dir / "alone/" + mask), bytesOf(dir / "out/b/" + mask)) << mask;
  }
}

TEST(SegmentCli, AFailingInputAmongSeveralEndsAlone) {
  const test::TempDir dir;
  for (const char* name : {"a", "b"}) {
    ASSERT_EQ(test::runCli("synth -o " + dir / name + " --frames 3 --size 160x120").exit_code, 0);
  }
  const test::CommandResult r = test::runCli("segment " + dir / "a" + " " + dir / "nothing.mp4" +
                                             " " + dir / "b" + " -o " + dir / "out" + " -q --threads 2");
  test::expectOneLineError(r, "nothing.mp4", test::kExitRunFailed);
  EXPECT_TRUE(fs::exists(dir / "out/a/00002.png"));
  EXPECT_TRUE(fs::exists(dir / "out/b/00002.png"));
  EXPECT_FALSE(fs::exists(dir / "out/nothing"));
}

TEST(SegmentCli, SeveralInputsRefusedBeforeAnyRun) {
  const test::TempDir dir;
  const std::string a = dir / "a", b = dir / "b";
  fs::create_directories(dir / "x");
  for (const std::string& clip : {a, b, dir / "x/a"}) {
    ASSERT_EQ(test::runCli("synth -o " + clip + " --frames 2 --size 160x120").exit_code, 0);
  }
  const std::string out = " -o " + dir / "out";
  test::expectOneLineError(test::runCli("segment " + a + " " + dir / "x/a" + out), "rename one",
                           test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + " " + b + out + " --show"), "--show",
                           test::kExitUsage);
  test::expectOneLineError(
      test::runCli("segment " + a + " " + b + out + " --stats " + dir / "s.jsonl"), "--stats",
      test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + " " + b + " -o " + a + "/frames/out"),
                           "into the input", test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + out + " --threads 0"), "--threads",
                           test::kExitUsage);
  // Checked for every input before any run, as for one: exit 2 (exit 1 before, one line per
  // input, or exit 0 with the outputs written at the top of ./a).
  test::expectOneLineError(test::runCli("segment " + a + " " + b + out + " --overlay x.gif"),
                           "--overlay", test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + " " + b + out + " --stats 00003.png"),
                           "--stats", test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + " " + b + " -o ''"), "-o",
                           test::kExitUsage);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// One input's outputs may not land in another input: its overlay folder, its stats file, its
// debug pictures written over the other's frames or video (exit 0 before, the input replaced).
TEST(SegmentCli, OneInputsOutputsStayOutOfTheOthers) {
  const test::TempDir dir;
  const std::string a = dir / "a";
  ASSERT_EQ(test::runCli("synth -o " + a + " --frames 2 --size 96x72").exit_code, 0);
  for (const char* inside : {"out/a/viz", "out/a/debug/mask", "out/a/st.png"}) {
    fs::create_directories((dir / inside).c_str());
    fs::copy(a + "/frames", dir / inside, fs::copy_options::recursive);
  }
  const std::string out = " -o " + dir / "out";
  test::expectOneLineError(
      test::runCli("segment " + a + " " + dir / "out/a/viz" + out + " --overlay viz"),
      "would write into the input", test::kExitUsage);
  test::expectOneLineError(
      test::runCli("segment " + a + " " + dir / "out/a/debug/mask" + out + " --debug"),
      "which the run's own pictures replace", test::kExitUsage);
  test::expectOneLineError(
      test::runCli("segment " + a + " " + dir / "out/a/st.png" + out + " --stats st.png"),
      "would write into the input", test::kExitUsage);
  EXPECT_EQ(test::filesIn(dir / "out/a/viz").size(), 2u);
}

// A sequence folder (frames/ in it) as the output folder: its masks would be read as its frames
// next time (accepted before; the next run segmented the masks). And a stats file named as the
// manifest's temporary file, which the manifest's write replaced.
TEST(SegmentCli, TheRunsFolderIsNoSequenceAndItsNamesAreItsOwn) {
  const test::TempDir dir;
  const std::string a = dir / "a";
  ASSERT_EQ(test::runCli("synth -o " + a + " --frames 2 --size 96x72").exit_code, 0);
  test::expectOneLineError(test::runCli("segment " + a + " -o " + a), "holds a sequence's frames/",
                           test::kExitUsage);
  test::expectOneLineError(test::runCli("segment " + a + " -o " + dir / "out" + " --stats " +
                                        dir / "out/movseg-run.json.part"),
                           "would overwrite the masks or the manifest", test::kExitUsage);
}

}  // namespace
}  // namespace movseg
