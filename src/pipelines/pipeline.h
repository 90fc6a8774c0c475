// The pipelines behind movseg::Segmenter, one per Params::method, made by one factory that
// switches on the method (as Ceres' LinearSolver::Create switches on its options). Each pipeline
// is one file that reads like its method's flow chart and calls the stages below it (motion/,
// classify/, cut/); no stage knows which pipeline calls it. Adding a method: docs/design.md.
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

class Pipeline {
 public:
  virtual ~Pipeline() = default;

  // Segments the next frame of the stream. `bgr` is 8-bit BGR, the pipeline's to keep. Returns
  // the mask (0 / 255) at any scale — the Segmenter scales it to the frame — and fills
  // result->features, the diagnostics of its stages, and `debug`.
  virtual cv::Mat process(const cv::Mat& bgr, const DebugSink& debug, Result* result) = 0;

  // Forgets the stream: the next frame is a first frame.
  virtual void reset() = 0;

  // The previous frame warped into the last frame's coordinates; empty when there is none.
  virtual cv::Mat compensatedPreviousFrame() const = 0;
};

// The pipeline of params.method; params must be valid (Params::check()).
std::unique_ptr<Pipeline> makePipeline(const Params& params);

// One per method, each in its own file.
std::unique_ptr<Pipeline> makePaperPipeline(const Params& params);
std::unique_ptr<Pipeline> makeDiffPipeline(const Params& params);
std::unique_ptr<Pipeline> makeMog2Pipeline(const Params& params);
std::unique_ptr<Pipeline> makeCompensatedMog2Pipeline(const Params& params);

}  // namespace movseg
