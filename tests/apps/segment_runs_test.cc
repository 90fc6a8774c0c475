// The CLI's threaded runs in-process: one stream on two threads (`segment --threads 2`) and
// several inputs at once (`segment IN1 IN2 ... --threads N`, `bench --threads N`) write the
// files of the one-thread runs byte for byte, and a failing input ends alone. SegmentRuns.* run
// in the ThreadSanitizer step (make test-tsan).
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "commands.h"
#include "concurrent.h"
#include "reliability/reliability_fixture.h"
#include "segment_run.h"
#include "test_support.h"

namespace movseg::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 6;

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A synthetic clip as numbered PNGs in `folder`.
std::string writeClip(const std::string& folder, std::uint64_t seed) {
  fs::create_directories(folder);
  const std::vector<cv::Mat> frames = test::synthFrames(kFrames, seed, {160, 120});
  for (size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/%05d.png", static_cast<int>(i));
    cv::imwrite(folder + name, frames[i]);
  }
  return folder;
}

SegmentOptions runOf(const std::string& input, const std::string& output, int threads = 1) {
  SegmentOptions options;
  options.input = input;
  options.output_dir = output;
  options.quiet = true;
  options.threads = threads;
  return options;
}

// The masks and the run manifest (no timings in either), byte for byte.
void expectSameFiles(const std::string& a, const std::string& b) {
  const std::vector<std::string> files = test::filesIn(a);
  ASSERT_EQ(files.size(), static_cast<size_t>(kFrames) + 1) << a;
  EXPECT_EQ(files, test::filesIn(b));
  for (const std::string& name : files) {
    EXPECT_EQ(bytesOf(a + "/" + name), bytesOf(b + "/" + name)) << b << "/" << name;
  }
}

TEST(SegmentRuns, OneStreamOnTwoThreadsWritesTheOneThreadFiles) {
  const test::TempDir dir;
  const std::string clip = writeClip(dir / "clip", 5);
  for (const int threads : {1, 2}) {
    EXPECT_EQ(runSegmentation(runOf(clip, dir / std::to_string(threads), threads)).frames, kFrames);
  }
  // equal empty masks would prove nothing
  ASSERT_GT(cv::countNonZero(cv::imread(dir / "1/00005.png", cv::IMREAD_GRAYSCALE)), 0);
  expectSameFiles(dir / "1", dir / "2");
}

// On two threads the frames are read ahead and the last one is still being segmented when the
// next read fails: it is written all the same, as on one thread.
TEST(SegmentRuns, ACorruptFrameEndsTheRunWithEveryFrameBeforeItWritten) {
  const test::TempDir dir;
  const std::string clip = writeClip(dir / "clip", 5);
  { std::ofstream(clip + "/00003.png", std::ios::trunc) << "garbage"; }
  for (const int threads : {1, 2}) {
    const std::string out = dir / std::to_string(threads);
    try {
      runSegmentation(runOf(clip, out, threads));
      ADD_FAILURE() << "no error on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("00003.png"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::exists(out + "/00002.png")) << threads;
    EXPECT_FALSE(fs::exists(out + "/00003.png")) << threads;
  }
}

// Two clips of images and a video, with an input that does not exist among them.
TEST(SegmentRuns, InputsAtOnceWriteWhatEachWritesAloneAndAFailureEndsAlone) {
  const test::TempDir dir;
  const std::string video = dir / "c.mkv";
  ASSERT_TRUE(test::ffmpeg("-framerate 10 -i " + writeClip(dir / "c", 7) +
                           "/%05d.png -c:v ffv1 " + video));
  const std::vector<std::string> inputs = {writeClip(dir / "a", 5), dir / "missing.mp4",
                                           writeClip(dir / "b", 6), video};
  std::vector<SegmentOptions> runs;
  for (const std::string& input : inputs) {
    runs.push_back(runOf(input, dir / "together/" + inputName(input)));
  }
  std::vector<size_t> ended;
  const std::vector<RunOutcome> outcomes =
      runSegmentations(runs, 3, [&](size_t i, const RunOutcome&) { ended.push_back(i); });
  std::sort(ended.begin(), ended.end());
  EXPECT_EQ(ended, (std::vector<size_t>{0, 1, 2, 3}));
  ASSERT_EQ(outcomes.size(), inputs.size());
  EXPECT_NE(outcomes[1].error.find("missing.mp4"), std::string::npos) << outcomes[1].error;
  for (const size_t i : {0, 2, 3}) {
    EXPECT_EQ(outcomes[i].error, "") << inputs[i];
    EXPECT_EQ(outcomes[i].summary.frames, kFrames) << inputs[i];
    const std::string alone = dir / "alone/" + inputName(inputs[i]);
    runSegmentation(runOf(inputs[i], alone));
    expectSameFiles(alone, runs[i].output_dir);
  }
}

TEST(SegmentRuns, EveryTaskRunsOnceAndTheFirstErrorStopsTheRest) {
  std::vector<std::atomic<int>> calls(50);
  runConcurrently(calls.size(), 3, [&](size_t i) { ++calls[i]; });
  EXPECT_TRUE(std::all_of(calls.begin(), calls.end(), [](const auto& c) { return c == 1; }));

  for (const int threads : {1, 2}) {
    std::atomic<int> started{0};
    std::vector<std::atomic<int>> runs(50);
    std::vector<std::thread::id> ran_on(50);  // each written by the one call of its index
    EXPECT_THROW(runConcurrently(50, threads,
                                 [&](size_t i) {
                                   ++started;
                                   ++runs[i];
                                   ran_on[i] = std::this_thread::get_id();
                                   if (i == 3) throw std::runtime_error("task 3");
                                 }),
                 std::runtime_error);
    if (threads == 1) {
      EXPECT_EQ(started, 4);
    }
    // On more threads, calls taken by the others before they saw the error may still start, as
    // many as the timing allows (not even "fewer than 50" is certain). What is certain: no call
    // runs twice, and the thread whose call threw starts no further one; each thread takes the
    // calls in order, so none of a higher index.
    EXPECT_EQ(runs[3], 1);
    for (size_t i = 0; i < runs.size(); ++i) {
      EXPECT_LE(runs[i], 1) << i;
      if (i > 3 && runs[i] == 1) {
        EXPECT_NE(ran_on[i], ran_on[3]) << threads << " threads: call " << i;
      }
    }
  }
  runConcurrently(0, 4, [](size_t) { FAIL(); });
}

TEST(InputNames, AsBatchNamesThem) {
  const test::TempDir dir;
  fs::create_directories(dir / "walk/frames");
  fs::create_directories(dir / "run");
  EXPECT_EQ(inputName(dir / "walk/frames"), "walk");
  EXPECT_EQ(inputName(dir / "walk/frames/"), "walk");
  EXPECT_EQ(inputName(dir / "run/"), "run");
  EXPECT_EQ(inputName("clips/walk.mp4"), "walk");
  EXPECT_EQ(inputName("rtsp://camera/live"), "live");
}

TEST(InputNames, PerInputRunsWriteIntoTheirOwnFolders) {
  const test::TempDir dir;
  SegmentOptions shared = runOf("", dir / "out");
  shared.stats_file = "stats.jsonl";
  shared.overlay = "overlay.mp4";
  const std::vector<SegmentOptions> runs = perInputRuns(shared, {"a.mp4", "b.mkv"});
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].input, "b.mkv");
  EXPECT_EQ(runs[1].output_dir, dir / "out/b");
  EXPECT_EQ(runs[1].stats_file, dir / "out/b/stats.jsonl");
  EXPECT_EQ(runs[1].overlay, dir / "out/b/overlay.mp4");
  EXPECT_THROW(perInputRuns(shared, {"x/a.mp4", "y/a.mkv"}), UsageError);
  shared.stats_file = dir / "stats.jsonl";
  EXPECT_THROW(perInputRuns(shared, {"a.mp4", "b.mkv"}), UsageError);
}

}  // namespace
}  // namespace movseg::cli
