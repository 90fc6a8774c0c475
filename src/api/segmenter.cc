// movseg::Segmenter: the frame loop, one frame at a time.
#include "movseg/segmenter.h"

#include "api/frame_loop.h"

namespace movseg {

struct Segmenter::Impl {
  explicit Impl(const Params& params) : loop(params), job(loop.newJob()) {}
  FrameLoop loop;
  std::unique_ptr<FrameLoop::Job> job;
};

Segmenter::Segmenter(const Params& params) {
  params.check();
  impl_ = std::make_unique<Impl>(params);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) {
  FrameLoop::Job& job = *impl_->job;
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
