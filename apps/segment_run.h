// The loop shared by `segment`, `demo` and `bench`: frames in, masks and diagnostics out.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "io/frame_source.h"
#include "latency.h"
#include "movseg/params.h"

namespace movseg::cli {

struct SegmentOptions {
  std::string input;          // io/frame_source.h's grammar
  std::string output_dir;     // masks as 00000.png, ... and the run manifest movseg-run.json
  std::string overlay;        // "" none; a folder, or a video file (.mp4, .mkv, .mov, .avi)
  bool feature_dots = true;   // the overlay shows the feature points
  bool show = false;          // the overlay in a live window; needs a display
  std::string stats_file;     // JSON Lines, one object per frame; "" none
  bool debug = false;         // write each stage's pictures under output_dir/debug/
  int max_frames = -1;        // < 0: all
  bool overwrite = false;     // replace the outputs of an earlier run in output_dir
  std::chrono::milliseconds timeout{10000};  // streams: open and read give up (0 = never)
  bool stop_on_decode_error = false;         // else decode errors are counted and reported
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
  int scene_cuts = 0;
  bool interrupted = false;
  bool reached_max_frames = false;
  SourceReport source;              // at the end of the run

  // The source gave fewer frames than its container announced (exactly, or by more than a
  // second of frames for an estimate), without being stopped.
  bool truncated() const;
};

// Throws UsageError (commands.h) for output paths that are empty, are the input or lie inside
// it, an overlay name that is neither a folder nor a video, or a folder holding an earlier
// run's outputs (without `overwrite`); std::runtime_error with a one-line message on bad input,
// a failed write, a decode error with stop_on_decode_error, or --show without a display. The
// files written before a failure stay complete under their final names.
SegmentSummary runSegmentation(const SegmentOptions& options);

// "123 frames in 1.2 s (101.3 fps, median 9.1 ms/frame)", and what went wrong with the input.
std::string describeSummary(const SegmentSummary& summary);

// What was wrong with the input ("3 decode errors (last: ...)", "47 of 104 frames: the video
// is truncated", "no frame for 10 s"), or "" when nothing was.
std::string describeInputProblems(const SegmentSummary& summary);

}  // namespace movseg::cli
