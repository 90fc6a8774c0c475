// A run stopped by SIGINT or SIGTERM midway leaves only complete files, says so in one line and
// exits with 130.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/video_decoder.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {
namespace fs = std::filesystem;

constexpr int kFrames = 150;

// Polls `done` every 5 ms until it holds (true) or `limit` has passed (false).
bool waitUntil(const std::function<bool()>& done, std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

bool waitForFile(const std::string& path, std::chrono::seconds limit) {
  return waitUntil([&] { return fs::exists(path); }, limit);
}

// Sends `signal` to the CLI run `pid` once it has written `file` (midway), waits for it and
// expects exit code 130.
void stopOnceWritten(pid_t pid, const std::string& file, int signal,
                     std::chrono::seconds patience) {
  const bool midway = waitForFile(file, patience);
  kill(pid, signal);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(midway) << file;
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);
}

// Waits until the process `pid` catches `signal` (its handler installed: SigCgt in
// /proc/<pid>/status), for a command that writes nothing midway to show how far it got.
bool waitForHandler(pid_t pid, int signal, std::chrono::seconds limit) {
  const auto catches = [&] {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line)) {
      if (line.rfind("SigCgt:", 0) != 0) continue;
      return ((std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1) != 0;
    }
    return false;
  };
  return waitUntil(catches, limit);
}

std::string textOf(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct Case {
  int signal;
  std::string threads;  // --threads: 2 reads ahead and writes behind on threads of their own
};

class Interrupt : public ::testing::TestWithParam<Case> {
 protected:
  static void SetUpTestSuite() {
    clip_ = new test::TempDir;
    const auto run = test::runCli("synth -o " + (*clip_ / "clip") + " --frames " +
                                  std::to_string(kFrames) + " --size 320x240");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete clip_; }
  static test::TempDir* clip_;
};
test::TempDir* Interrupt::clip_ = nullptr;

TEST_P(Interrupt, MidwayLeavesCompleteFilesAndExits130) {
  test::TempDir dir;
  const std::string out = dir / "out", stats = dir / "out/stats.jsonl";
  const std::string overlay = dir / "overlay.mp4";
  const pid_t pid = test::startCli({"segment", *clip_ / "clip/frames", "-o", out, "--stats", stats,
                                    "--overlay", overlay, "-q", "--threads", GetParam().threads},
                                   dir / "log.txt");
  ASSERT_GT(pid, 0);
  // The sixth mask exists: the run is midway, its signal handler installed.
  ASSERT_NO_FATAL_FAILURE(
      stopOnceWritten(pid, out + "/00005.png", GetParam().signal, std::chrono::seconds(120)));

  int masks = 0;
  for (const std::string& name : test::filesIn(out)) {
    if (name == "stats.jsonl" || name == "movseg-run.json") continue;
    ASSERT_EQ(fs::path(name).extension(), ".png") << name;  // no *.part left behind
    const cv::Mat mask = cv::imread(out + "/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(mask.empty()) << name;
    EXPECT_EQ(mask.size(), cv::Size(320, 240)) << name;
    ++masks;
  }
  EXPECT_GE(masks, 6);
  EXPECT_LT(masks, kFrames);
  EXPECT_EQ(textOf(dir / "log.txt"), "movseg: interrupted after " + std::to_string(masks) +
                                         " frames; the files written so far are complete\n");
  std::ifstream lines(stats);
  std::string line;
  int frame = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(nlohmann::json::parse(line).at("frame").get<int>(), frame) << line;
    ++frame;
  }
  EXPECT_EQ(frame, masks);
  const nlohmann::json manifest = nlohmann::json::parse(textOf(out + "/movseg-run.json"));
  EXPECT_EQ(manifest.at("frames_done").get<int>(), masks);
  EXPECT_FALSE(manifest.at("finished").get<bool>());
  // The overlay video is closed, not cut off: it plays, one frame per mask, as its index says.
  VideoDecoder video(overlay, {});
  EXPECT_EQ(video.expectedFrames(), masks);
  int played = 0;
  for (cv::Mat picture; video.read(&picture);) ++played;
  EXPECT_EQ(played, masks);
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  return (info.param.signal == SIGINT ? "SIGINT_" : "SIGTERM_") + info.param.threads + "threads";
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt,
                         ::testing::Values(Case{SIGINT, "1"}, Case{SIGTERM, "1"}, Case{SIGINT, "2"}),
                         caseName);

// Several inputs at once share one signal handler: SIGINT stops both runs after their current
// frame, and each input's folder holds complete masks and an unfinished manifest.
class InterruptSeveral : public Interrupt {};

TEST_F(InterruptSeveral, StopsEveryRunWithCompleteFiles) {
  test::TempDir dir;
  const std::string clip = *clip_ / "clip", other = dir / "other";
  fs::create_directory_symlink(clip, other);
  const std::string out = dir / "out";
  const pid_t pid = test::startCli({"segment", clip, other, "-o", out, "-q", "--threads", "2"},
                                   dir / "log.txt");
  ASSERT_NO_FATAL_FAILURE(
      stopOnceWritten(pid, out + "/clip/00005.png", SIGINT, std::chrono::seconds(120)));
  const std::string log = textOf(dir / "log.txt");
  EXPECT_EQ(log.rfind("movseg: interrupted after ", 0), 0u) << log;
  for (const char* name : {"clip", "other"}) {
    int masks = 0;
    for (const std::string& file : test::filesIn(out + "/" + name)) {
      if (file == "movseg-run.json") continue;
      ASSERT_EQ(fs::path(file).extension(), ".png") << file;  // no *.part left behind
      ASSERT_FALSE(cv::imread(out + "/" + name + "/" + file, cv::IMREAD_UNCHANGED).empty()) << file;
      ++masks;
    }
    EXPECT_LT(masks, kFrames) << name;
    const nlohmann::json manifest =
        nlohmann::json::parse(textOf(out + "/" + name + "/movseg-run.json"));
    EXPECT_EQ(manifest.at("frames_done").get<int>(), masks) << name;
    EXPECT_FALSE(manifest.at("finished").get<bool>()) << name;
  }
}

// bench stops as segment does: one line, exit 130, and no scratch folder left in /tmp.
class InterruptBench : public Interrupt {};

TEST_F(InterruptBench, StopsWithoutATableAndRemovesItsScratchFolder) {
  test::TempDir dir;
  const pid_t pid =
      test::startCli({"bench", *clip_ / "clip", "--methods", "dense", "--json", dir / "bench.json"},
                     dir / "log.txt");
  ASSERT_GT(pid, 0);
  const std::string scratch =
      (fs::temp_directory_path() / ("movseg-bench-" + std::to_string(pid))).string();
  ASSERT_NO_FATAL_FAILURE(
      stopOnceWritten(pid, scratch + "/dense/clip/00005.png", SIGINT, std::chrono::seconds(60)));
  const std::string log = textOf(dir / "log.txt");
  EXPECT_NE(log.find("movseg: interrupted"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(scratch));
  EXPECT_FALSE(fs::exists(dir / "bench.json"));
}

// eval heeds a signal between sequences (README, "Bad input"): of 40 sequences it scores the
// one it is on, then stops with one line, exit 130 and no report.
class InterruptEval : public Interrupt {};

TEST_F(InterruptEval, StopsBetweenSequencesWithoutAReport) {
  test::TempDir dir;
  const std::string data = dir / "data";
  fs::create_directories(data);
  for (int i = 0; i < 40; ++i) {
    fs::create_directory_symlink(*clip_ / "clip", data + "/s" + std::to_string(i));
  }
  const pid_t pid = test::startCli({"eval", data, data, "--json", dir / "eval.json"},
                                   dir / "log.txt");
  ASSERT_GT(pid, 0);
  const bool handled = waitForHandler(pid, SIGINT, std::chrono::seconds(60));
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(handled);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(textOf(dir / "log.txt"),
            "movseg: interrupted; the files written so far are complete\n");
  EXPECT_FALSE(fs::exists(dir / "eval.json"));
}

// demo stops as segment does, without scoring the frames it did not segment.
class InterruptDemo : public Interrupt {};

TEST_F(InterruptDemo, StopsWithoutAScore) {
  test::TempDir dir;
  const pid_t pid = test::startCli(
      {"demo", "-o", dir / "demo", "--frames", std::to_string(kFrames)}, dir / "log.txt");
  ASSERT_GT(pid, 0);
  ASSERT_NO_FATAL_FAILURE(stopOnceWritten(pid, dir / "demo/segmented/00005.png", SIGTERM,
                                          std::chrono::seconds(120)));
  const std::string log = textOf(dir / "log.txt");
  EXPECT_NE(log.find("movseg: interrupted after "), std::string::npos) << log;
  EXPECT_EQ(log.find("demo: J"), std::string::npos) << log;
}

}  // namespace
}  // namespace movseg
