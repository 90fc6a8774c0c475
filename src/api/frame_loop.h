// The one frame loop behind Segmenter and StreamSegmenter. Phase 1 normalises the frame,
// restarts the stream when its size changes and runs the pipeline's analysis; phase 2 runs the
// pipeline's segmentation, empties a first frame's mask, scales the mask to the frame and
// times the whole.
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
    std::unique_ptr<Analysis> analysis;
    Result result;
    cv::Size size;
    double analyse_ms = 0;
  };

  std::unique_ptr<Job> newJob() const;

  // The frame as the pipeline takes it: 8-bit BGR in a buffer of the loop's own (the pipeline
  // keeps frames, and a video loop refills its buffer). Throws std::invalid_argument for an
  // empty frame or an unsupported type.
  cv::Mat ownedBgr(const cv::Mat& frame);

  // Phase 1 of `bgr` (from ownedBgr) into `job`.
  void analyse(const cv::Mat& bgr, Job* job);

  // Phase 2: completes job->result.
  void segment(Job* job);

  // The next frame starts a new stream.
  void reset();

  const Params& params() const { return params_; }
  const Pipeline& pipeline() const { return *pipeline_; }

 private:
  Params params_;
  std::unique_ptr<Pipeline> pipeline_;
  cv::Size size_;  // of the last analysed frame; empty before the first frame of a stream
  FramePool frames_;
};

}  // namespace movseg
