// The pipelines behind movseg::Segmenter, one per Params::method, made by one factory that
// switches on the method (as Ceres' LinearSolver::Create switches on its options). Each pipeline
// is one file that reads like its method's flow chart and calls the stages below it (motion/,
// classify/, cut/, flow/, evidence/, refine/); no stage knows which pipeline calls it. Adding a
// method: docs/design.md.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

// Where the stages' debug pictures go (Result::debug, Params::debug_images). A picture is drawn
// only when pictures are wanted.
class DebugSink {
 public:
  explicit DebugSink(std::map<std::string, cv::Mat>* pictures = nullptr) : pictures_(pictures) {}

  // Stores draw() under `name` when pictures are wanted; draw is not called otherwise.
  template <typename Draw>
  void put(const std::string& name, Draw&& draw) const {
    if (pictures_ != nullptr) (*pictures_)[name] = draw();
  }

 private:
  std::map<std::string, cv::Mat>* pictures_;
};

// What a pipeline learns from one frame before it segments it. Each pipeline derives its own;
// the frame loop keeps two and hands them out in turn, so that their buffers are allocated once
// and the previous frame's analysis stays intact while the next one is made (a pipeline may
// keep references into it).
struct Analysis {
  virtual ~Analysis() = default;
  bool first_frame = false;  // no previous frame: stream start, reset() or a size change
  // Where nothing moves, at the frame's size (CV_8U, non-zero there), or empty: the region the
  // user said to ignore (Segmenter::setIgnoredRegion). The frame loop clears the mask there; a
  // pipeline that can also keeps it out of what it measures.
  cv::Mat ignored;
};

// A method in two phases, so that a stream can overlap them on two threads: phase 1 (analyse)
// of frame t+1 runs while phase 2 (segment) of frame t does. Phase 1 depends on the frames
// alone, never on an earlier segmentation; each phase runs in stream order.
class Pipeline {
 public:
  virtual ~Pipeline() = default;

  virtual std::unique_ptr<Analysis> newAnalysis() const = 0;

  // Phase 1: analyses the next frame into `analysis` (whose first_frame the caller has set).
  // `bgr` is 8-bit BGR, the pipeline's to keep.
  virtual void analyse(const cv::Mat& bgr, Analysis* analysis) = 0;

  // Phase 2: the mask of the analysed frame (CV_8U, above 127 moving, at any scale: the frame
  // loop scales it to the frame and makes it 0 / 255); fills result->features, the diagnostics
  // of the pipeline's stages, and `debug`. A first-frame analysis makes it forget what it
  // remembers of earlier frames.
  virtual cv::Mat segment(const Analysis& analysis, const DebugSink& debug, Result* result) = 0;

  // Forgets phase 1's stream; phase 2 forgets at the next first-frame analysis. It runs with
  // phase 1, possibly while phase 2 segments the previous frame on another thread
  // (StreamSegmenter), so it must not touch phase 2's state.
  virtual void reset() = 0;

  // The previous frame warped into the last analysed frame's coordinates; empty when there is
  // none.
  virtual cv::Mat compensatedPreviousFrame() const = 0;
};

// The pipeline of params.method; params must be valid (Params::check()).
std::unique_ptr<Pipeline> makePipeline(const Params& params);

// One per method, each in its own file.
std::unique_ptr<Pipeline> makePaperPipeline(const Params& params);
std::unique_ptr<Pipeline> makeDiffPipeline(const Params& params);
std::unique_ptr<Pipeline> makeMog2Pipeline(const Params& params);
std::unique_ptr<Pipeline> makeCompensatedMog2Pipeline(const Params& params);
std::unique_ptr<Pipeline> makeDensePipeline(const Params& params);

}  // namespace movseg
