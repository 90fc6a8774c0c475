// movseg::Segmenter: the one frame loop. It normalises each frame, restarts the stream when the
// frame size changes, runs the pipeline of Params::method, scales the mask to the frame and
// times the call.
#include "movseg/segmenter.h"

#include "core/frame.h"
#include "core/timing.h"
#include "pipelines/pipeline.h"

namespace movseg {

struct Segmenter::Impl {
  explicit Impl(const Params& p) : params(p), pipeline(makePipeline(p)) {}
  Params params;
  std::unique_ptr<Pipeline> pipeline;
  cv::Size size;  // of the last frame; empty before the first frame of a stream
};

Segmenter::Segmenter(const Params& params) {
  params.check();
  impl_ = std::make_unique<Impl>(params);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  // The pipeline keeps the frame for the next pair, so it must not share the caller's buffer:
  // a video loop (cap >> frame) refills that buffer with the next frame.
  cv::Mat bgr = toBgr8(frame);
  if (bgr.data == frame.data) bgr = bgr.clone();
  Result result;
  Diagnostics& diag = result.diagnostics;
  if (!impl_->size.empty() && impl_->size != bgr.size()) {
    impl_->pipeline->reset();
    impl_->size = cv::Size();
    diag.reset = true;
  }
  diag.first_frame = impl_->size.empty();
  impl_->size = bgr.size();
  const DebugSink debug(impl_->params.debug_images ? &result.debug : nullptr);
  const cv::Mat mask = impl_->pipeline->process(bgr, debug, &result);
  // Nothing moves without a previous frame, whatever a pipeline makes of its first one (MOG2
  // calls everything foreground).
  result.mask = diag.first_frame ? cv::Mat::zeros(bgr.size(), CV_8U) : upscaledMask(mask, bgr.size());
  debug.put("mask", [&] { return result.mask; });
  diag.total_ms = millisecondsSince(start);
  return result;
}

void Segmenter::reset() {
  impl_->pipeline->reset();
  impl_->size = cv::Size();
}

cv::Mat Segmenter::compensatedPreviousFrame() const {
  return impl_->pipeline->compensatedPreviousFrame();
}

const Params& Segmenter::params() const { return impl_->params; }

}  // namespace movseg
