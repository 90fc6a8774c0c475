// The loop shared by `segment`, `demo` and `bench`: frames in, masks and diagnostics out.
#pragma once

#include <chrono>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
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
  std::string ignore;         // "" none; an image, white (above 127) where nothing moves
                              // (Segmenter::setIgnoredRegion), scaled to the frames
  bool quiet = false;         // no progress, no summary line
  cv::Size resize;            // non-empty: frames are resized to this before segmentation and
                              // the masks back to the frame's own size (bench --size)
  int threads = 1;            // the stream's: 1, or 2 to cut a frame while the next one is
                              // analysed (StreamSegmenter), the one after read and the one
                              // before written, each on a thread of its own (the same files)
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

  // The source ended early without being stopped: fewer frames than its container counts, or,
  // where the count is estimated from a duration, its frames' timestamps more than a second
  // short of that duration (a variable frame rate makes the estimate wrong, not the time).
  bool truncated() const;
};

// Throws UsageError (commands.h) for output paths that are empty, are the input or lie inside
// it, an overlay name that is neither a folder nor a video, or a folder holding an earlier
// run's outputs (without `overwrite`); std::runtime_error with a one-line message on bad input
// (an `ignore` image that cannot be read among it, before anything is written),
// a failed write, a decode error with stop_on_decode_error, or --show without a display. The
// files written before a failure stay complete under their final names.
SegmentSummary runSegmentation(const SegmentOptions& options);

// While one lives, SIGINT and SIGTERM end runSegmentation after the current frame (a blocking
// read of a stream gives up at once) and it returns, interrupted; what was written stays
// complete. Scopes nest: runs at once (several inputs, bench --threads) and a batch around them
// share one installation. The first scope clears the stop and installs the handlers, the last
// restores the previous ones; a signal between two runs of a batch is so not lost.
class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  static bool stopped();  // a signal came since the first scope began
};

// Throws UsageError "OPTION 'PATH' would write into the input 'INPUT'" when `path` is
// `input_path` (the file or folder on disk that `input` names, as inputPath() gives it) or lies
// inside it, once both are made absolute and normal. Empty names are not checked.
void refuseWritingIntoInput(const std::string& option, const std::string& path,
                            const std::string& input, const std::string& input_path);

// The report files of `eval` and `bench` (an option and its path; empty paths are not checked),
// before any work: none inside one of `inputs` (files, or folders such as those a dataset's
// sequences are read from, sequenceFolders()) nor the same file as one in them through a link,
// where it could replace a mask or a frame (UsageError); no two in one file (UsageError); each
// one writable (std::runtime_error), tried only once the others are known to be no input.
void checkReportPaths(std::initializer_list<std::pair<const char*, std::string>> reports,
                      const std::vector<std::string>& inputs);

// One run per element of `runs`, as runSegmentation does, `threads` runs at a time, each on one
// thread; a run that fails ends alone. `ended` is called as each run ends, one call at a time.
// After SIGINT or SIGTERM the runs in progress stop after their current frame and no run
// starts. Returns each run's outcome, in the order of `runs`.
struct RunOutcome {
  SegmentSummary summary;
  std::string error;  // the one-line reason it failed; "" when it did not
};
std::vector<RunOutcome> runSegmentations(
    const std::vector<SegmentOptions>& runs, int threads,
    const std::function<void(size_t index, const RunOutcome& outcome)>& ended);

// The runs of `segment IN1 IN2 ... -o OUTDIR`: `shared` for each input, its outputs in
// OUTDIR/<name>/ (inputName). Throws UsageError for two inputs of one name, an output folder
// inside an input, --show, or a --stats or --overlay value that is not a plain file name (with
// several inputs they name a file in each input's folder).
std::vector<SegmentOptions> perInputRuns(const SegmentOptions& shared,
                                         const std::vector<std::string>& inputs);

// An input's name for its output folder, as `python3 -m movseg batch` names it: 'clips/walk.mp4'
// is 'walk', a folder its own name, and a layout folder ('walk/frames') its parent's.
std::string inputName(const std::string& input);

// "123 frames in 1.20 s (101.3 fps overall, median 9.10 ms/frame)", and what went wrong with
// the input.
std::string describeSummary(const SegmentSummary& summary);

// What was wrong with the input ("3 decode errors (last: ...)", "47 of 104 frames: the video
// is truncated", "no frame within the timeout: the stream stalled"), or "" when nothing was.
std::string describeInputProblems(const SegmentSummary& summary);

}  // namespace movseg::cli
