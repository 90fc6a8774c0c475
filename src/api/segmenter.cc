// movseg::Segmenter: the frame loop, one frame at a time.
#include "movseg/segmenter.h"

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
  FrameLoop::Job& job = *impl_->jobs[impl_->next];
  impl_->next = 1 - impl_->next;
  impl_->loop.analyse(impl_->loop.ownedBgr(frame), &job);
  impl_->loop.segment(&job);
  return std::move(job.result);
}

void Segmenter::reset() { impl_->loop.reset(); }

cv::Mat Segmenter::compensatedPreviousFrame() const {
  return impl_->loop.pipeline().compensatedPreviousFrame();
}

const Params& Segmenter::params() const { return impl_->loop.params(); }

}  // namespace movseg
