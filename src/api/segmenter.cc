// movseg::Segmenter: the frame loop, one frame at a time.
#include "movseg/segmenter.h"

#include <stdexcept>

#include "api/frame_loop.h"

namespace movseg {

struct Segmenter::Impl {
  explicit Impl(const Params& params) : loop(params), jobs{loop.newJob(), loop.newJob()} {}
  FrameLoop loop;
  // In turn, as in a stream: a pipeline may keep references into the previous frame's analysis.
  std::unique_ptr<FrameLoop::Job> jobs[2];
  int next = 0;
};

Segmenter::Segmenter(const Params& params) {
  params.check();
  impl_ = std::make_unique<Impl>(params);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) {
  Impl& s = *impl_;
  const cv::Mat bgr = s.loop.ownedBgr(frame);  // std::invalid_argument: nothing has changed
  FrameLoop::Job& job = *s.jobs[s.next];
  s.next = 1 - s.next;
  try {
    s.loop.analyse(bgr, &job);
    s.loop.segment(&job);
  } catch (const std::runtime_error&) {
    reset();  // the pipeline may hold half a pair
    throw;
  }
  return std::move(job.result);
}

void Segmenter::reset() { impl_->loop.reset(); }

void Segmenter::setIgnoredRegion(const cv::Mat& region) { impl_->loop.setIgnoredRegion(region); }

cv::Mat Segmenter::compensatedPreviousFrame() const {
  return impl_->loop.compensatedPreviousFrame();
}

const Params& Segmenter::params() const { return impl_->loop.params(); }

}  // namespace movseg
