// A video file or stream decoded by FFmpeg's libraries directly, frame by frame. OpenCV's reader
// hides what a reliable run needs: it converts every frame at the size the container announced
// (a stream whose size changes midway comes out scrambled at the old size), mutes the decoder's
// errors, and waits 30 s on a silent server whatever a signal says. Here each frame comes out at
// its own decoded size, every error FFmpeg reports is counted, and every blocking call gives up
// at a deadline or as soon as a stop flag is set.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

namespace movseg {

struct DecoderLimits {
  // Opening, and each read, give up after this long without progress (0 = wait forever).
  std::chrono::milliseconds timeout{0};
  // When set (by a signal handler), a blocking open or read returns within 0.1 s.
  const std::atomic<bool>* stop = nullptr;
  // Frames of more pixels are not decoded (a decode error); 0 = FFmpeg's own limit. A small
  // file can claim a huge frame, as an image header can (docs/reliability.md).
  std::int64_t max_pixels = 0;
};

class VideoDecoder {
 public:
  // Opens `url` (a file path or anything FFmpeg's protocols take) and its best video stream.
  // Throws std::runtime_error with FFmpeg's reason in one line when it cannot.
  VideoDecoder(const std::string& url, const DecoderLimits& limits);
  ~VideoDecoder();
  VideoDecoder(const VideoDecoder&) = delete;
  VideoDecoder& operator=(const VideoDecoder&) = delete;

  // The next frame as 8-bit BGR at its decoded size, turned upright when the stream says it is
  // rotated; false at the end of the stream, at the deadline (timedOut()) or when stopped.
  bool read(cv::Mat* bgr);

  // Frames the container says the stream holds: exact when it stores the count (mp4), else
  // estimated from its duration and frame rate (exactCount() false); -1 when it says nothing.
  int expectedFrames() const { return expected_frames_; }
  bool exactCount() const { return exact_count_; }
  double fps() const { return fps_; }
  // Where the count is estimated, the stream's duration in seconds (else -1), and the time of
  // the last frame read, from the stream's start (-1 before one, or without timestamps): a
  // variable frame rate makes the estimate wrong, the time does not.
  double durationSeconds() const { return exact_count_ ? -1 : duration_seconds_; }
  double reachedSeconds() const { return reached_seconds_; }

  // Errors FFmpeg reported so far (failed reads and decodes, its error messages, frames it
  // marked corrupt), and the last one's text.
  int errors() const { return errors_; }
  const std::string& lastError() const { return last_error_; }
  // A read gave up at the deadline: the stream stalled, and whatever ended it after is no end.
  bool timedOut() const { return timed_out_; }

  // Called by FFmpeg: its messages and its polls for giving up.
  void noteLogMessage(const std::string& text);
  bool shouldGiveUp();

 private:
  void open(const std::string& url);
  void noteError(const std::string& text);
  void noteError(int code);
  bool sendNextPacket();
  void noteTimestamp();  // of the frame just decoded, into reached_seconds_
  void convert(cv::Mat* bgr);
  void restartDeadline();

  struct FFmpeg;
  std::unique_ptr<FFmpeg> ff_;
  DecoderLimits limits_;
  std::chrono::steady_clock::time_point deadline_;
  int expected_frames_ = -1;
  bool exact_count_ = false;
  double fps_ = 0;
  double duration_seconds_ = -1, reached_seconds_ = -1;
  double rotation_ = 0;  // degrees, counter-clockwise, from the stream's display matrix
  int errors_ = 0;
  std::string last_error_;
  bool timed_out_ = false;
  bool logged_ = false;    // FFmpeg logged an error during the current call
  bool draining_ = false;  // the demuxer ended: the decoder gives out what it holds
};

}  // namespace movseg
