#include "movseg/stream_segmenter.h"

#include <stdexcept>

#include "api/frame_loop.h"
#include "core/worker.h"

namespace movseg {

struct StreamSegmenter::Impl {
  Impl(const Params& params, int thread_count)
      : loop(params), jobs{loop.newJob(), loop.newJob()} {
    if (thread_count == 2) worker = std::make_unique<Worker>();
  }

  FrameLoop loop;
  // In turn, frame after frame (a pipeline may keep references into the previous frame's
  // analysis, as Segmenter's jobs): the pending one and the next one.
  std::unique_ptr<FrameLoop::Job> jobs[2];
  int next = 0;      // the job of the next frame pushed, whether or not flush() came between
  int pending = -1;  // the job analysed but not segmented, if any
  cv::Mat incoming;                // the frame being analysed
  std::unique_ptr<Worker> worker;  // null with one thread

  // Forgets the stream; a failed phase ends it (the pipeline may hold half a pair).
  void restart() {
    pending = -1;
    loop.reset();
  }

  // Waits for the analysis in flight, if any.
  void settle() {
    if (!worker) return;
    try {
      worker->wait();
    } catch (...) {
      restart();
      throw;
    }
  }

  // Phase 1 of the incoming frame into `job`, on the worker when there is one.
  void analyseIncoming(FrameLoop::Job* job) {
    if (worker) {
      worker->start([this, job] { loop.analyse(incoming, job); });  // small: no allocation
      return;
    }
    try {
      loop.analyse(incoming, job);
    } catch (...) {
      restart();
      throw;
    }
  }

  std::optional<Result> segmentPending() {
    if (pending < 0) return std::nullopt;
    FrameLoop::Job& job = *jobs[pending];
    pending = -1;
    try {
      loop.segment(&job);
    } catch (...) {
      settle();
      restart();
      throw;
    }
    return std::move(job.result);
  }
};

StreamSegmenter::StreamSegmenter(const Params& params, int threads) {
  params.check();
  if (threads != 1 && threads != 2) {
    throw std::invalid_argument("StreamSegmenter: threads must be 1 or 2");
  }
  impl_ = std::make_unique<Impl>(params, threads);
}

StreamSegmenter::~StreamSegmenter() = default;

std::optional<Result> StreamSegmenter::push(const cv::Mat& frame) {
  Impl& s = *impl_;
  s.settle();
  s.incoming = s.loop.ownedBgr(frame);
  const int slot = s.next;
  s.next = 1 - slot;
  s.analyseIncoming(s.jobs[slot].get());
  std::optional<Result> previous = s.segmentPending();  // while the worker analyses the frame
  s.pending = slot;
  return previous;
}

std::optional<Result> StreamSegmenter::flush() {
  impl_->settle();
  return impl_->segmentPending();
}

void StreamSegmenter::reset() {
  impl_->settle();
  impl_->restart();
}

void StreamSegmenter::setIgnoredRegion(const cv::Mat& region) {
  impl_->settle();  // the analysis in flight reads the loop's region
  impl_->loop.setIgnoredRegion(region);
}

const Params& StreamSegmenter::params() const { return impl_->loop.params(); }

}  // namespace movseg
