// movseg::Segmenter: the one frame loop. It checks and normalises each frame, restarts the
// stream when the frame size changes, runs the pipeline of Params::method within the work limit
// of the frame size, scales the mask to the frame and times the call. No exception of OpenCV's
// leaves it: each becomes the std::invalid_argument or std::runtime_error segmenter.h promises.
#include "movseg/segmenter.h"

#include <climits>
#include <stdexcept>
#include <string>

#include "core/frame.h"
#include "core/timing.h"
#include "core/work_limit.h"
#include "pipelines/pipeline.h"

namespace movseg {
namespace {

std::string sizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// OpenCV's warps (remap) take images below SHRT_MAX pixels a side; both working scales must fit.
void checkWorkingScales(cv::Size frame, const Params& params) {
  for (const auto& [name, width] : {std::pair<const char*, int>{"alignment_width", params.alignment_width},
                                    {"segmentation_width", params.segmentation_width}}) {
    const cv::Size scaled = scaledSize(frame, width);
    if (scaled.width >= SHRT_MAX || scaled.height >= SHRT_MAX) {
      throw std::invalid_argument("frame " + sizeText(frame) + " is too large: at " + name + " " +
                                  std::to_string(width) + " it is " + sizeText(scaled) +
                                  ", beyond 32766 pixels a side");
    }
  }
}

// The one line of an OpenCV error (what() spans several), for std::runtime_error.
std::runtime_error openCvFailure(const cv::Exception& e) {
  return std::runtime_error("OpenCV failed in " + e.func + ": " + e.err);
}

}  // namespace

struct Segmenter::Impl {
  explicit Impl(const Params& p) : params(p) {}
  Result process(const cv::Mat& frame);

  Params params;
  std::unique_ptr<Pipeline> pipeline;
  cv::Size size;  // of the last frame; empty before the first frame of a stream
  bool work_limited = false;
};

Segmenter::Segmenter(const Params& params) {
  params.check();
  impl_ = std::make_unique<Impl>(params);
}
Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

Result Segmenter::process(const cv::Mat& frame) {
  try {
    return impl_->process(frame);
  } catch (const std::invalid_argument&) {
    throw;  // the frame was refused before anything changed
  } catch (const cv::Exception& e) {
    reset();  // the pipeline may hold half a pair
    throw openCvFailure(e);
  } catch (const std::bad_alloc&) {
    reset();
    throw std::runtime_error("out of memory");
  }
}

Result Segmenter::Impl::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  if (frame.empty()) throw std::invalid_argument("empty frame");
  checkWorkingScales(frame.size(), params);
  // The pipeline keeps the frame for the next pair, so it must not share the caller's buffer:
  // a video loop (cap >> frame) refills that buffer with the next frame.
  cv::Mat bgr = toBgr8(frame);
  if (bgr.data == frame.data) bgr = bgr.clone();
  Result result;
  Diagnostics& diag = result.diagnostics;
  diag.reset = !size.empty() && size != bgr.size();
  if (size.empty() || diag.reset) {
    // A new stream: its pipeline works within the limit of its frame size.
    const WorkLimit limit = withinWorkLimit(params, bgr.size());
    work_limited = limit.lowered;
    pipeline = makePipeline(limit.params);
  }
  diag.first_frame = size.empty() || diag.reset;
  diag.work_limited = work_limited;
  size = bgr.size();
  const DebugSink debug(params.debug_images ? &result.debug : nullptr);
  const cv::Mat mask = pipeline->process(bgr, debug, &result);
  // Nothing moves without a previous frame, whatever a pipeline makes of its first one (MOG2
  // calls everything foreground), nor across a scene cut, where everything differs.
  result.mask = diag.first_frame || diag.scene_cut ? cv::Mat::zeros(bgr.size(), CV_8U)
                                                   : upscaledMask(mask, bgr.size());
  debug.put("mask", [&] { return result.mask; });
  diag.total_ms = millisecondsSince(start);
  return result;
}

void Segmenter::reset() {
  if (impl_->pipeline != nullptr) impl_->pipeline->reset();
  impl_->size = cv::Size();
}

cv::Mat Segmenter::compensatedPreviousFrame() const {
  if (impl_->pipeline == nullptr) return cv::Mat();
  try {
    return impl_->pipeline->compensatedPreviousFrame();
  } catch (const cv::Exception& e) {
    throw openCvFailure(e);
  }
}

const Params& Segmenter::params() const { return impl_->params; }

}  // namespace movseg
