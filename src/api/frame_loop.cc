#include "api/frame_loop.h"

#include <stdexcept>

#include "core/timing.h"

namespace movseg {

FrameLoop::FrameLoop(const Params& params) : params_(params), pipeline_(makePipeline(params)) {}

std::unique_ptr<FrameLoop::Job> FrameLoop::newJob() const {
  auto job = std::make_unique<Job>();
  job->analysis = pipeline_->newAnalysis();
  return job;
}

cv::Mat FrameLoop::ownedBgr(const cv::Mat& frame) {
  if (frame.empty()) throw std::invalid_argument("empty frame");
  cv::Mat bgr = frames_.take(frame.size(), CV_8UC3);
  toBgr8(frame, &bgr);
  return bgr;
}

void FrameLoop::analyse(const cv::Mat& bgr, Job* job) {
  const Clock::time_point start = Clock::now();
  job->result = Result();
  Diagnostics& diag = job->result.diagnostics;
  if (!size_.empty() && size_ != bgr.size()) {
    pipeline_->reset();
    size_ = cv::Size();
    diag.reset = true;
  }
  diag.first_frame = job->analysis->first_frame = size_.empty();
  size_ = job->size = bgr.size();
  pipeline_->analyse(bgr, job->analysis.get());
  job->analyse_ms = millisecondsSince(start);
}

void FrameLoop::segment(Job* job) {
  const Clock::time_point start = Clock::now();
  Result& result = job->result;
  const DebugSink debug(params_.debug_images ? &result.debug : nullptr);
  const cv::Mat mask = pipeline_->segment(*job->analysis, debug, &result);
  // Nothing moves without a previous frame, whatever a pipeline makes of its first one (MOG2
  // calls everything foreground).
  result.mask = result.diagnostics.first_frame ? cv::Mat::zeros(job->size, CV_8U)
                                               : upscaledMask(mask, job->size);
  debug.put("mask", [&] { return result.mask; });
  result.diagnostics.total_ms = job->analyse_ms + millisecondsSince(start);
}

void FrameLoop::reset() {
  pipeline_->reset();
  size_ = cv::Size();
}

}  // namespace movseg
