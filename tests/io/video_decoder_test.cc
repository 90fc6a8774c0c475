// The FFmpeg reader: every frame at its decoded size, decode errors counted, truncation visible,
// a deadline on every blocking call.
#include "io/video_decoder.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "test_support.h"

namespace movseg {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

// `frames` frames of FFmpeg's test pattern as H.264.
std::string testVideo(const test::TempDir& dir, const std::string& name, const std::string& size,
                      int frames, const std::string& extra = "") {
  const std::string path = dir / name;
  EXPECT_TRUE(test::ffmpeg("-f lavfi -i testsrc=size=" + size + ":rate=25 -frames:v " +
                           std::to_string(frames) + " -c:v libx264 -pix_fmt yuv420p " + extra + " " +
                           path));
  return path;
}

std::vector<cv::Mat> allFrames(VideoDecoder& decoder) {
  std::vector<cv::Mat> frames;
  cv::Mat frame;
  while (decoder.read(&frame)) frames.push_back(frame);
  return frames;
}

// Two H.264 parts of different sizes joined without re-encoding (FFmpeg's concat demuxer), as
// issue 15 found them: OpenCV's reader gives every frame at the first size, scrambled.
std::string sizeChangingVideo(const test::TempDir& dir, const std::string& extension) {
  testVideo(dir, "a.mp4", "160x120", 10);
  testVideo(dir, "b.mp4", "128x96", 10);
  { std::ofstream(dir / "list.txt") << "file 'a.mp4'\nfile 'b.mp4'\n"; }
  const std::string joined = dir / ("joined." + extension);
  EXPECT_TRUE(test::ffmpeg("-f concat -safe 0 -i " + dir / "list.txt" + " -c copy " + joined));
  return joined;
}

class SizeChange : public ::testing::TestWithParam<std::string> {};

TEST_P(SizeChange, EveryFrameComesAtItsDecodedSizeAndUnscrambled) {
  const test::TempDir dir;
  VideoDecoder joined(sizeChangingVideo(dir, GetParam()), {});
  VideoDecoder second(dir / "b.mp4", {});
  const std::vector<cv::Mat> frames = allFrames(joined), alone = allFrames(second);
  ASSERT_EQ(frames.size(), 20u);
  ASSERT_EQ(alone.size(), 10u);
  for (size_t i = 0; i < 10; ++i) EXPECT_EQ(frames[i].size(), cv::Size(160, 120)) << i;
  for (size_t i = 0; i < 10; ++i) {
    ASSERT_EQ(frames[10 + i].size(), cv::Size(128, 96)) << i;
    EXPECT_EQ(cv::norm(frames[10 + i], alone[i], cv::NORM_INF), 0) << i;
  }
  EXPECT_EQ(joined.errors(), 0) << joined.lastError();
}

INSTANTIATE_TEST_SUITE_P(Containers, SizeChange, ::testing::Values("mp4", "mkv"));

TEST(VideoDecoder, ReportsTheContainersFrameCountAndRate) {
  const test::TempDir dir;
  VideoDecoder mp4(testVideo(dir, "a.mp4", "64x48", 12), {});
  EXPECT_EQ(mp4.expectedFrames(), 12);
  EXPECT_TRUE(mp4.exactCount());
  EXPECT_DOUBLE_EQ(mp4.fps(), 25.0);
  EXPECT_EQ(allFrames(mp4).size(), 12u);
  VideoDecoder mkv(testVideo(dir, "a.mkv", "64x48", 12), {});
  EXPECT_EQ(mkv.expectedFrames(), 12);  // from its duration
  EXPECT_FALSE(mkv.exactCount());
}

// A phone held upright stores landscape frames and a rotation: each frame comes out upright,
// the stored frame turned as FFmpeg's own tools turn it. `-metadata:s:v:0 rotate=90` writes a
// display matrix of 90 degrees counterclockwise (ffprobe: rotation=90), which `ffmpeg -i` then
// turns counterclockwise (checked by hand; OpenCV 4.6's reader turns it the other way).
TEST(VideoDecoder, TurnsFramesUprightAsTheStreamSays) {
  const test::TempDir dir;
  const std::string stored = testVideo(dir, "stored.mp4", "160x120", 5);
  const std::string turned = dir / "turned.mp4";
  ASSERT_TRUE(test::ffmpeg("-i " + stored + " -c copy -metadata:s:v:0 rotate=90 " + turned));
  VideoDecoder stored_decoder(stored, {}), turned_decoder(turned, {});
  const std::vector<cv::Mat> landscape = allFrames(stored_decoder);
  const std::vector<cv::Mat> upright = allFrames(turned_decoder);
  ASSERT_EQ(upright.size(), 5u);
  ASSERT_EQ(landscape.size(), 5u);
  for (size_t i = 0; i < upright.size(); ++i) {
    ASSERT_EQ(upright[i].size(), cv::Size(120, 160)) << i;
    cv::Mat expected;
    cv::rotate(landscape[i], expected, cv::ROTATE_90_COUNTERCLOCKWISE);
    EXPECT_EQ(cv::norm(upright[i], expected, cv::NORM_INF), 0) << i;
  }
}

TEST(VideoDecoder, TruncationShowsAsFewerFramesThanExpected) {
  const test::TempDir dir;
  const std::string path = testVideo(dir, "a.mp4", "160x120", 50, "-movflags +faststart");
  fs::resize_file(path, fs::file_size(path) / 2);
  VideoDecoder decoder(path, {});
  EXPECT_EQ(decoder.expectedFrames(), 50);
  const size_t frames = allFrames(decoder).size();
  EXPECT_LT(frames, 40u);
  EXPECT_GE(frames, 10u);  // what the first half holds is decoded (measured: 10)
}

TEST(VideoDecoder, DamageIsCountedAsDecodeErrors) {
  const test::TempDir dir;
  const std::string path = testVideo(dir, "a.mkv", "160x120", 50);
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(path) * 4 / 10));
    std::mt19937 random(1);
    for (int i = 0; i < 4096; ++i) file.put(static_cast<char>(random()));
  }
  VideoDecoder decoder(path, {});
  EXPECT_GT(allFrames(decoder).size(), 0u);
  EXPECT_GT(decoder.errors(), 0);
  EXPECT_FALSE(decoder.lastError().empty());
}

TEST(VideoDecoder, OpeningASilentServerGivesUpAtTheTimeout) {
  const test::LocalServer server;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(VideoDecoder(server.url(), {milliseconds(500), nullptr}), std::runtime_error);
  // At the timeout: not at once (another failure), not long after.
  EXPECT_GE(std::chrono::steady_clock::now() - start, milliseconds(450));
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(3000));
}

TEST(VideoDecoder, AStopFlagEndsAnOpenWithinASecond) {
  const test::LocalServer server;
  std::atomic<bool> stop{false};
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(milliseconds(300));
    stop = true;
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(VideoDecoder(server.url(), {milliseconds(0), &stop}), std::runtime_error);
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(1300));
  stopper.join();
}

}  // namespace
}  // namespace movseg
