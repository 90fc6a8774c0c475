// The one frame loop behind Segmenter and StreamSegmenter. Phase 1 normalises the frame,
// restarts the stream when its size changes, keeps each stream within the work limit of its
// frame size and runs the pipeline's analysis; phase 2 runs the pipeline's segmentation,
// empties the mask of a first frame or a scene cut, scales the mask to the frame and times the
// whole. No OpenCV exception leaves it: each becomes the std::invalid_argument or
// std::runtime_error that segmenter.h promises.
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "core/frame.h"
#include "movseg/params.h"
#include "movseg/segmenter.h"
#include "pipelines/pipeline.h"

namespace movseg {

class FrameLoop {
 public:
  explicit FrameLoop(const Params& params);

  // One frame on its way through the loop; reused from frame to frame.
  struct Job {
    std::shared_ptr<Pipeline> pipeline;  // the one that analysed it, and segments it
    std::unique_ptr<Analysis> analysis;
    Result result;
    cv::Size size;
    double analyse_ms = 0;
  };

  std::unique_ptr<Job> newJob() const;

  // The frame as the pipeline takes it: 8-bit BGR in a buffer of the loop's own (the pipeline
  // keeps frames, and a video loop refills its buffer). Throws std::invalid_argument for an
  // empty frame, an unsupported type, or a frame too large for OpenCV's warps at a working
  // scale; nothing has changed then.
  cv::Mat ownedBgr(const cv::Mat& frame);

  // Phase 1 of `bgr` (from ownedBgr) into `job`. Throws std::runtime_error when OpenCV fails
  // (out of memory above all); the caller then resets the loop.
  void analyse(const cv::Mat& bgr, Job* job);

  // Phase 2: completes job->result. Throws as analyse() does.
  void segment(Job* job);

  // The next frame starts a new stream.
  void reset();

  // The region of the frames to ignore from the next analysed frame on (Segmenter's).
  void setIgnoredRegion(const cv::Mat& region);

  const Params& params() const { return params_; }

  // The pipeline's compensatedPreviousFrame(), empty after reset(); throws as analyse() does.
  cv::Mat compensatedPreviousFrame() const;

 private:
  void startStream(cv::Size size);
  // The ignored region at `size`, made again only when the size or the region changes.
  const cv::Mat& ignoredAt(cv::Size size);
  // What the analysis of `bgr` ignores: that region, and the black bars around the picture
  // (Params::black_bars; diag->black_bars says whether there are), joined again only when the
  // bars or the region change.
  cv::Mat ignoredIn(const cv::Mat& bgr, Diagnostics* diag);

  Params params_;
  // The current stream's pipeline, made with the parameters of its work limit. A new one
  // replaces it only when those parameters change; the previous stream's last job keeps the
  // old one alive until it is segmented (StreamSegmenter's phases overlap).
  std::shared_ptr<Pipeline> pipeline_;
  bool work_limited_ = false;  // pipeline_ runs with lowered parameters
  cv::Size size_;  // of the last analysed frame; empty before the first frame of a stream
  FramePool frames_;
  FramePool masks_;  // of the results' masks: a caller that lets a result go gives it back
  cv::Mat ignored_;          // as the user gave it, 0 / 255; empty: none
  cv::Mat ignored_at_size_;  // scaled to the last frame's size; analyses share it, never written
  // The last frame's bars joined to ignored_at_size_ (held, so that its buffer is not reused),
  // inside the picture `picture_`; analyses share it, never written.
  cv::Mat with_bars_, joined_to_;
  cv::Rect picture_;
};

}  // namespace movseg
