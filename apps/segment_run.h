// The loop shared by `segment`, `demo` and `bench`: frames in, masks and diagnostics out.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "latency.h"
#include "movseg/params.h"

namespace movseg::cli {

struct SegmentOptions {
  std::string input;
  std::string output_dir;     // masks as 00000.png, ...; empty = do not write masks
  std::string overlay;        // "" none; a folder, or a video file (.mp4, .avi, .mkv)
  bool show = false;          // the overlay in a live window; needs a display
  std::string stats_file;     // JSON Lines, one object per frame; "" none
  bool debug = false;         // write each stage's pictures under output_dir/debug/
  int max_frames = -1;        // < 0: all
  Params params;              // params.method chooses the pipeline
  bool quiet = false;         // no progress, no summary line
  cv::Size resize;            // non-empty: frames are resized to this before segmentation and
                              // the masks back to the frame's own size (bench --size)
};

struct SegmentSummary {
  int frames = 0;
  double seconds = 0;               // wall time of the whole run
  LatencyHistogram frame_ms;        // per-frame process() time
  int resets = 0;
  int motion_fallbacks = 0;
  bool interrupted = false;
  // A source of unknown length (stream, camera) stopped giving frames: it ended or stalled
  // (OpenCV's FFmpeg backend gives up on a silent stream after its read timeout, 30 s).
  bool stream_ended = false;
};

// Throws std::runtime_error with a one-line message on bad input, unwritable output, or --show
// without a display.
SegmentSummary runSegmentation(const SegmentOptions& options);

// "123 frames in 1.2 s (101.3 fps, median 9.1 ms/frame)".
std::string describeSummary(const SegmentSummary& summary);

}  // namespace movseg::cli
