#include "api/frame_loop.h"

#include <climits>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "core/black_bars.h"
#include "core/timing.h"
#include "core/work_limit.h"

namespace movseg {
namespace {

std::string sizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// OpenCV's warps (remap) take images below SHRT_MAX pixels a side; both working scales must fit.
void checkWorkingScales(cv::Size frame, const Params& params) {
  for (const auto& [name, width] : {std::pair<const char*, int>{"alignment_width", params.alignment_width},
                                    {"segmentation_width", params.segmentation_width}}) {
    const cv::Size scaled = workingSize(frame, width);
    if (scaled.width >= SHRT_MAX || scaled.height >= SHRT_MAX) {
      throw std::invalid_argument("frame " + sizeText(frame) + " is too large: at " + name + " " +
                                  std::to_string(width) + " it is " + sizeText(scaled) +
                                  ", beyond 32766 pixels a side");
    }
  }
}

// Runs `step`; an OpenCV error (whose what() spans several lines) or a failed allocation leaves
// as a one-line std::runtime_error.
template <typename Step>
auto openCvChecked(Step&& step) {
  try {
    return step();
  } catch (const cv::Exception& e) {
    throw std::runtime_error("OpenCV failed in " + e.func + ": " + e.err);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("out of memory");
  }
}

}  // namespace

FrameLoop::FrameLoop(const Params& params) : params_(params), pipeline_(makePipeline(params)) {}

std::unique_ptr<FrameLoop::Job> FrameLoop::newJob() const {
  auto job = std::make_unique<Job>();
  job->analysis = pipeline_->newAnalysis();
  return job;
}

cv::Mat FrameLoop::ownedBgr(const cv::Mat& frame) {
  if (frame.empty()) throw std::invalid_argument("empty frame");
  if (frame.dims != 2) {
    throw std::invalid_argument("a frame has 2 dimensions (rows, columns; then channels), not " +
                                std::to_string(frame.dims));
  }
  checkWorkingScales(frame.size(), params_);
  return openCvChecked([&] {
    cv::Mat bgr = frames_.take(frame.size(), CV_8UC3);
    toBgr8(frame, &bgr);
    return bgr;
  });
}

void FrameLoop::analyse(const cv::Mat& bgr, Job* job) {
  const Clock::time_point start = Clock::now();
  job->result = Result();
  Diagnostics& diag = job->result.diagnostics;
  if (!size_.empty() && size_ != bgr.size()) {
    reset();
    diag.reset = true;
  }
  diag.first_frame = job->analysis->first_frame = size_.empty();
  if (diag.first_frame) startStream(bgr.size());
  diag.work_limited = work_limited_;
  size_ = job->size = bgr.size();
  job->pipeline = pipeline_;
  openCvChecked([&] {
    job->analysis->ignored = ignoredIn(bgr, &diag);
    pipeline_->analyse(bgr, job->analysis.get());
  });
  job->analyse_ms = millisecondsSince(start);
}

void FrameLoop::segment(Job* job) {
  const Clock::time_point start = Clock::now();
  Result& result = job->result;
  const DebugSink debug(params_.debug_images ? &result.debug : nullptr);
  openCvChecked([&] {
    const cv::Mat mask = job->pipeline->segment(*job->analysis, debug, &result);
    // Nothing moves without a previous frame, whatever a pipeline makes of its first one (MOG2
    // calls everything foreground), nor across a scene cut, where everything differs.
    const Diagnostics& diag = result.diagnostics;
    result.mask = masks_.take(job->size, CV_8U);
    if (diag.first_frame || diag.scene_cut) {
      result.mask.setTo(0);
    } else {
      upscaledMask(mask, job->size, &result.mask);
      const cv::Mat& ignored = job->analysis->ignored;
      if (!ignored.empty()) clearWhere(ignored, &result.mask);
    }
  });
  debug.put("mask", [&] { return result.mask; });
  result.diagnostics.total_ms = job->analyse_ms + millisecondsSince(start);
}

void FrameLoop::reset() {
  pipeline_->reset();
  size_ = cv::Size();
}

cv::Mat FrameLoop::compensatedPreviousFrame() const {
  if (size_.empty()) return cv::Mat();  // no stream since reset(): nothing to warp
  return openCvChecked([&] { return pipeline_->compensatedPreviousFrame(); });
}

void FrameLoop::setIgnoredRegion(const cv::Mat& region) {
  if (!region.empty() && (region.type() != CV_8UC1 || region.dims != 2)) {
    throw std::invalid_argument(
        "the ignored region must be an 8-bit image with one channel, non-zero where ignored");
  }
  cv::Mat binary;
  if (!region.empty()) cv::compare(region, 0, binary, cv::CMP_NE);
  ignored_ = binary;
  ignored_at_size_ = cv::Mat();  // analyses in flight keep the old one
}

// Nearest neighbours: the region stays 0 / 255, and a region drawn on a frame of the input's
// size is that frame's pixels exactly.
const cv::Mat& FrameLoop::ignoredAt(cv::Size size) {
  if (ignored_.empty() || ignored_at_size_.size() == size) return ignored_at_size_;
  cv::Mat scaled;  // a new buffer: the analyses hold the last one
  cv::resize(ignored_, scaled, size, 0, 0, cv::INTER_NEAREST);
  ignored_at_size_ = scaled;
  return ignored_at_size_;
}

cv::Mat FrameLoop::ignoredIn(const cv::Mat& bgr, Diagnostics* diag) {
  const cv::Mat& named = ignoredAt(bgr.size());
  if (!params_.black_bars) return named;
  const cv::Rect picture = pictureInsideBlackBars(bgr);
  diag->black_bars = picture.size() != bgr.size();
  if (!diag->black_bars) return named;
  if (with_bars_.size() == bgr.size() && picture == picture_ && named.data == joined_to_.data) {
    return with_bars_;
  }
  cv::Mat joined(bgr.size(), CV_8U);  // a new buffer: the analyses hold the last one
  for (int y = 0; y < bgr.rows; ++y) {
    uchar* row = joined.ptr<uchar>(y);
    const uchar* by_user = named.empty() ? nullptr : named.ptr<uchar>(y);
    const bool picture_row = y >= picture.y && y < picture.br().y;
    for (int x = 0; x < bgr.cols; ++x) {
      const bool bar = !picture_row || x < picture.x || x >= picture.br().x;
      row[x] = bar || (by_user != nullptr && by_user[x] != 0) ? 255 : 0;
    }
  }
  with_bars_ = joined;
  joined_to_ = named;
  picture_ = picture;
  return with_bars_;
}

// A stream runs within the work limit of its frame size (core/work_limit.h). The defaults never
// reach it, so a stream of default parameters keeps the pipeline made with the loop.
void FrameLoop::startStream(cv::Size size) {
  const WorkLimit limit = withinWorkLimit(params_, size);
  if (limit.lowered || work_limited_) pipeline_ = makePipeline(limit.params);
  work_limited_ = limit.lowered;
}

}  // namespace movseg
