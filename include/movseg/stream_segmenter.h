// A stream segmented on two threads: while one frame is segmented, the next is analysed
// (prepared, its motion estimated). The masks are bit-identical to Segmenter::process's.
#pragma once

#include <memory>
#include <optional>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

class StreamSegmenter {
 public:
  // threads: 1 (the phases in turn, on the caller's thread) or 2 (the next frame's analysis on a
  // thread of the segmenter's own). Throws std::invalid_argument when params.check() fails or
  // threads is not 1 or 2.
  explicit StreamSegmenter(const Params& params = Params(), int threads = 2);
  ~StreamSegmenter();
  StreamSegmenter(const StreamSegmenter&) = delete;
  StreamSegmenter& operator=(const StreamSegmenter&) = delete;

  // Takes the next frame (as Segmenter::process does) and returns the result of the frame
  // pushed before it — nothing on a stream's first push. Throws as Segmenter::process does:
  // std::invalid_argument for a frame it does not take (the frame is then not taken),
  // std::runtime_error when OpenCV fails (the stream restarts).
  std::optional<Result> push(const cv::Mat& frame);

  // The result of the last frame pushed, once; nothing when there is none waiting.
  std::optional<Result> flush();

  // Forgets the stream, dropping a result not yet returned (flush() first to keep it).
  void reset();

  // As Segmenter::setIgnoredRegion, from the next frame pushed on. Waits for the analysis in
  // flight first, and throws its failure as push() would (the stream then restarts).
  void setIgnoredRegion(const cv::Mat& region);

  const Params& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace movseg
