// Equal input and seed give bit-identical masks across OpenCV thread counts, concurrent
// Segmenters and separate CLI processes (run after run: contract_test.cc, for every method).
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

constexpr int kFrames = 12;

// OpenCV's parallel_for splits resize, blur and warp across its threads; none of it may change
// a bit. (The CLI runs single-threaded; the library uses OpenCV's setting.)
TEST(Determinism, OneOrTwoOpenCvThreadsGiveTheSameMasks) {
  const std::vector<cv::Mat> frames = test::synthFrames(kFrames, 2);
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const std::vector<cv::Mat> one = test::masksOf(frames);
  cv::setNumThreads(2);
  const std::vector<cv::Mat> two = test::masksOf(frames);
  cv::setNumThreads(threads);
  ASSERT_GT(cv::countNonZero(one.back()), 0);  // equal empty masks would prove nothing
  EXPECT_TRUE(test::identical(one, two));
}

// Segmenters share no mutable state: two streams on two threads at once give what each gives
// alone.
TEST(Determinism, TwoSegmentersOnTwoThreadsGiveWhatEachGivesAlone) {
  const std::vector<cv::Mat> a = test::synthFrames(kFrames, 3), b = test::synthFrames(kFrames, 4);
  const std::vector<cv::Mat> alone_a = test::masksOf(a), alone_b = test::masksOf(b);
  std::vector<cv::Mat> together_a, together_b;
  std::thread ta([&] { together_a = test::masksOf(a); });
  std::thread tb([&] { together_b = test::masksOf(b); });
  ta.join();
  tb.join();
  ASSERT_GT(cv::countNonZero(alone_a.back()), 0);
  ASSERT_GT(cv::countNonZero(alone_b.back()), 0);
  EXPECT_TRUE(test::identical(alone_a, together_a));
  EXPECT_TRUE(test::identical(alone_b, together_b));
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(Determinism, TwoCliRunsWriteIdenticalMaskFiles) {
  test::TempDir dir;
  const std::string frames = std::to_string(kFrames);
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames " + frames).exit_code, 0);
  for (const char* out : {"run1", "run2"}) {
    const auto run =
        test::runCli("segment " + (dir / "clip/frames") + " -o " + (dir / out) + " -q");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  const std::vector<std::string> files = test::filesIn(dir / "run1");
  ASSERT_EQ(files.size(), static_cast<size_t>(kFrames) + 1);  // and the run manifest
  EXPECT_EQ(files, test::filesIn(dir / "run2"));
  // equal empty masks would prove nothing
  ASSERT_GT(cv::countNonZero(cv::imread(dir / "run1/00011.png", cv::IMREAD_GRAYSCALE)), 0);
  for (const std::string& name : files) {
    EXPECT_EQ(bytesOf(dir / ("run1/" + name)), bytesOf(dir / ("run2/" + name))) << name;
  }
}

}  // namespace
}  // namespace movseg
