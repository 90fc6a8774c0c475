// movseg segment INPUT... -o OUTDIR [--threads N] [--overlay [PATH]] [--show] [--debug] ...
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "params_options.h"
#include "segment_run.h"

namespace movseg::cli {
namespace {

// What went wrong with a completed run's input, or "".
std::string inputFailure(const SegmentSummary& summary) {
  const std::string problems = describeInputProblems(summary);
  return problems.empty() ? "" : problems + "; the files written are complete";
}

// One input: its stream on up to two threads (the next frame analysed while this one is cut).
void segmentOne(SegmentOptions options, int threads) {
  options.threads = std::min(threads, 2);
  const SegmentSummary summary = runSegmentation(options);
  throwIfInterrupted(summary.frames, summary.interrupted);
  if (!options.quiet) std::cout << "segment: " << describeSummary(summary) << std::endl;
  const std::string failure = inputFailure(summary);
  if (!failure.empty()) throw std::runtime_error("'" + options.input + "': " + failure);
}

// Several inputs: `threads` at a time, each on one thread, into OUTDIR/<name>/. A failing input
// reports its error and the others go on; the exit status says whether any failed.
void segmentMany(const SegmentOptions& shared, const std::vector<std::string>& inputs,
                 int threads) {
  std::vector<SegmentOptions> runs = perInputRuns(shared, inputs);
  for (SegmentOptions& run : runs) run.quiet = true;  // bars of runs at once would mix
  int failed = 0, frames = 0;
  bool interrupted = false;
  runSegmentations(runs, threads, [&](size_t i, const RunOutcome& outcome) {
    const std::string failure =
        outcome.error.empty() ? inputFailure(outcome.summary) : outcome.error;
    frames += outcome.summary.frames;
    interrupted = interrupted || outcome.summary.interrupted;
    if (!failure.empty()) {
      ++failed;
      std::cerr << "movseg: error: " << oneLine("'" + runs[i].input + "': " + failure) << std::endl;
    } else if (!shared.quiet && !outcome.summary.interrupted) {
      std::cout << "segment: " << oneLine(runs[i].input) << ": "
                << describeSummary(outcome.summary) << std::endl;
    }
  });
  throwIfInterrupted(frames, interrupted || StopOnSignal::stopped());
  if (!shared.quiet) {
    std::cout << "segment: " << runs.size() - failed << " of " << runs.size() << " inputs done in "
              << shared.output_dir << std::endl;
  }
  if (failed > 0) throw CLI::RuntimeError(kExitRunFailed);  // each failure has said why
}

}  // namespace

void addSegmentCommand(CLI::App& app) {
  auto options = std::make_shared<SegmentOptions>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto threads = std::make_shared<int>(1);
  CLI::App* cmd = app.add_subcommand("segment", "Segment the moving objects of a video");
  cmd->add_option("INPUT", *inputs,
                  "Video file, folder of images (in number order), camera index or stream URL; "
                  "with several, each one's outputs go to OUTDIR/<name>/")
      ->required();
  cmd->add_option("-o,--output", options->output_dir, "Folder for the masks 00000.png, ...")
      ->required();
  cmd->add_option("--threads", *threads,
                  "From 2, one INPUT is pipelined (the next frame analysed while this one is "
                  "cut, reading and writing on threads of their own; the same files); several "
                  "INPUTs run N at a time, one thread each")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--overlay", options->overlay,
                  "Overlay pictures: a folder (PNG frames) or a video file (.mp4, .mkv, .mov: "
                  "H.264 at the input's frame rate; .avi: Motion JPEG); without a value, "
                  "OUTDIR/overlay/")
      ->expected(0, 1)
      ->default_str("");
  cmd->add_flag_callback("--no-feature-dots", [options] { options->feature_dots = false; },
                         "The overlay shows the mask only, not the feature points");
  cmd->add_flag("--show", options->show,
                "Show the overlay in a live window (needs a display; q or Esc stops)");
  cmd->add_flag("--debug", options->debug, "Write each stage's pictures to OUTDIR/debug/<stage>/");
  cmd->add_option("--max-frames", options->max_frames, "Stop after N frames (at least 1)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cmd->add_option("--stats", options->stats_file, "Per-frame diagnostics as JSON Lines");
  cmd->add_option("--ignore", options->ignore,
                  "An image, white where nothing moves: what is fixed to the camera (a bonnet, "
                  "a timestamp), scaled to the frames")
      ->type_name("IMAGE");
  cmd->add_flag("--overwrite", options->overwrite,
                "Replace the outputs of an earlier run in OUTDIR (else such a folder is refused)");
  auto timeout = std::make_shared<double>(10);
  cmd->add_option("--timeout", *timeout,
                  "Seconds a stream may take to open or to give the next frame (0 = no limit)")
      ->check(CLI::Range(0.0, 86400.0).description(""))
      ->type_name("SECONDS")
      ->capture_default_str();
  cmd->add_flag("--stop-on-decode-error", options->stop_on_decode_error,
                "Stop at the first decode error (else they are counted, and reported at the end)");
  cmd->add_flag("-q,--quiet", options->quiet, "No progress bar and no summary");
  addParamsOptions(cmd, &options->params);
  cmd->callback([options, inputs, threads, cmd, timeout] {
    refuseEmptyNames(*cmd, {"--stats", "--ignore"});
    // CLI11's range lets NaN through (every comparison with it is false); it would wait forever.
    if (std::isnan(*timeout)) throw UsageError("--timeout: nan is not a number of seconds");
    const bool several = inputs->size() > 1;
    if (cmd->count("--overlay") > 0 && options->overlay.empty()) {
      options->overlay = several ? "overlay" : options->output_dir + "/overlay";
    }
    // Whole milliseconds, at least one for any time given: 0 ms means "no limit".
    options->timeout = std::chrono::milliseconds(
        *timeout > 0 ? std::max(1LL, std::llround(*timeout * 1000)) : 0LL);
    // From here to the end: a signal after the last run ended still stops the command (exit
    // 130), rather than killing it as the default handlers, restored with the runs', would.
    const StopOnSignal stop_on_signal;
    if (several) {
      segmentMany(*options, *inputs, *threads);
    } else {
      options->input = inputs->front();
      segmentOne(*options, *threads);
    }
  });
}

}  // namespace movseg::cli
