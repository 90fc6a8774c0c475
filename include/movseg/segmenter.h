// movseg — moving object segmentation for freely moving cameras, online, frame by frame.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

// Label of a feature point after §3.2: background (F_b), foreground (F_f), or unknown (removed
// from either set by the colour GMMs; the cut decides it).
enum class FeatureLabel : std::uint8_t { kBackground = 0, kForeground = 1, kUnknown = 2 };

struct Feature {
  cv::Point2f position;  // full-resolution pixel coordinates in the current frame
  FeatureLabel label = FeatureLabel::kUnknown;
};

// What happened while one frame was processed; the fields are listed in movseg/diagnostics.def.
struct Diagnostics {
#define MOVSEG_DIAGNOSTIC(type, name, default_value, unit, doc) type name = default_value;
#include "movseg/diagnostics.def"
#undef MOVSEG_DIAGNOSTIC
};

struct Result {
  cv::Mat mask;  // CV_8U, 0 / 255, same size as the input frame
  std::vector<Feature> features;
  Diagnostics diagnostics;
  // Each stage's pictures, by name, when Params::debug_images is set (see docs/design.md).
  std::map<std::string, cv::Mat> debug;
};

// Segments the moving objects of a video, one frame at a time: each frame's mask depends on it
// and the frames before it only (`paper` compares it with the previous frame; `dense` also
// carries the last mask, colour models and the last pairs' depth). Not thread-safe: use one
// Segmenter per stream.
class Segmenter {
 public:
  // Throws std::invalid_argument when params.check() fails.
  explicit Segmenter(const Params& params = Params());
  ~Segmenter();
  // A Segmenter moved from holds no stream: it may only be assigned to or destroyed (as a
  // std::unique_ptr moved from may only be reset), never called.
  Segmenter(Segmenter&&) noexcept;
  Segmenter& operator=(Segmenter&&) noexcept;
  Segmenter(const Segmenter&) = delete;
  Segmenter& operator=(const Segmenter&) = delete;

  // Takes the next frame: grey, BGR or BGRA (RGB: convert it first, cv::COLOR_RGB2BGR), at
  // least 1x1; 8-bit or 16-bit, or float (32 or 64 bits) with values in [0, 1] — a float frame
  // in 0-255 is rejected. Returns the mask of what moves in it; never throws for a hard scene
  // (flat, noisy, scene cut): see Diagnostics' flags. Each stream runs within the per-frame work
  // limit of its frame size (Diagnostics::work_limited). No OpenCV exception leaves it; it
  // throws only:
  //  - std::invalid_argument (Python: ValueError) for a frame it does not take: empty, an
  //    unsupported type, a float value outside [0, 1], or too large for OpenCV's warps at a
  //    working scale (a side of 32767 pixels or more at alignment_width or
  //    segmentation_width). Nothing has changed: the next frame continues the stream.
  //  - std::runtime_error (Python: RuntimeError) when OpenCV fails on a frame it took (out of
  //    memory above all). The stream restarts: the next frame is a first frame.
  Result process(const cv::Mat& frame);

  // Forgets the previous frame: the next frame is treated as a first frame.
  void reset();

  // Pixels that never move, from the next frame on: what is fixed to the camera (a dash-cam's
  // bonnet, a burnt-in timestamp or logo, a robot's own arm) stands still in the image while the
  // world moves, and would be taken for a mover. `region`: CV_8U with one channel, non-zero
  // where ignored, of any size (scaled to each frame's, nearest neighbour); empty: none. The
  // mask is 0 there for every method; `dense` also leaves it, and a margin around it as wide
  // as the flow's reach, out of its evidence, the camera's fit, the residual's scale, the
  // photometric check's unit and the scene-cut test. Black bars around the picture are joined
  // to it on every frame (Params::black_bars). Throws std::invalid_argument for another type;
  // nothing has changed then.
  void setIgnoredRegion(const cv::Mat& region);

  // The previous frame warped into the last processed frame's coordinates (8-bit BGR); empty
  // before the second frame, and always with `mog2`, which fits no camera model. Throws
  // std::runtime_error when OpenCV cannot warp it (a frame of 32767 pixels or more a side).
  cv::Mat compensatedPreviousFrame() const;

  const Params& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace movseg
