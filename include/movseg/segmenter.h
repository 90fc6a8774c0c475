// movseg — moving object segmentation for freely moving cameras, online, two frames at a time.
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

// Wall time of each stage of one process() call, in milliseconds.
struct Timings {
  double prepare_ms = 0;   // colour conversion, downscaling, pyramid, feature detection
  double motion_ms = 0;    // §3.1 tracking and two-layer RANSAC
  double classify_ms = 0;  // §3.2 compensated difference, eq. (3), GMM refinement
  double cut_ms = 0;       // §3.3 geodesic distances and max-flow
  double total_ms = 0;
};

struct Diagnostics {
  // Frame-to-frame camera model mapping previous-frame pixel coordinates to current-frame
  // pixel coordinates (full resolution). Affine models have a last row of (0, 0, 1).
  cv::Matx33d model = cv::Matx33d::eye();
  bool model_is_affine = true;
  int features = 0;            // feature points detected in the previous frame
  int tracks = 0;              // of those, tracked by LK forward and backward
  int matches = 0;             // of those, kept by the ZNCC and forward–backward filters (S_m)
  int background_matches = 0;  // final S_b
  int foreground_matches = 0;  // final S_f
  int outer_iterations = 0;    // outer layers of Algorithm 1 run
  int foreground_seeds = 0;    // F_f after GMM refinement
  int background_seeds = 0;    // F_b after GMM refinement
  int unknown_seeds = 0;       // removed by the GMMs
  double lambda = 0;           // the threshold of eq. (3) used for this pair
  int cut_nodes = 0;           // pixels left to max-flow after fixing the decided ones
  bool first_frame = false;    // no previous frame: empty mask
  bool reset = false;          // frame size changed: the segmenter restarted on this frame
  bool motion_fallback = false;  // too few matches: previous model (or identity) reused
  bool no_background_seeds = false;  // F_b empty: the mask comes from eq. (3) alone
  Timings timings;
};

struct Result {
  cv::Mat mask;  // CV_8U, 0 / 255, same size as the input frame
  std::vector<Feature> features;
  Diagnostics diagnostics;
  // Each stage's pictures, by name, when Params::debug_images is set (see docs/design.md).
  std::map<std::string, cv::Mat> debug;
};

// Segments the moving objects of a video, one frame at a time. Each call compares the frame
// with the previous one only. Not thread-safe: use one Segmenter per stream.
class Segmenter {
 public:
  // Throws std::invalid_argument when params.check() fails.
  explicit Segmenter(const Params& params = Params());
  ~Segmenter();
  Segmenter(Segmenter&&) noexcept;
  Segmenter& operator=(Segmenter&&) noexcept;
  Segmenter(const Segmenter&) = delete;
  Segmenter& operator=(const Segmenter&) = delete;

  // Takes the next frame: 8-bit or 16-bit, grey, BGR or BGRA, at least 1x1. Returns the mask of
  // what moves in it. Throws std::invalid_argument for an empty frame or an unsupported type;
  // never throws for a hard scene (flat, noisy, scene cut): see Diagnostics' flags.
  Result process(const cv::Mat& frame);

  // Forgets the previous frame: the next frame is treated as a first frame.
  void reset();

  // The previous frame warped into the last processed frame's coordinates (8-bit BGR); empty
  // before the second frame.
  cv::Mat compensatedPreviousFrame() const;

  const Params& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace movseg
