// movseg segment INPUT -o OUTDIR [--overlay [PATH]] [--show] [--debug] [--static] ...
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.h"
#include "params_options.h"
#include "segment_run.h"

namespace movseg::cli {

void addSegmentCommand(CLI::App& app) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* cmd = app.add_subcommand("segment", "Segment the moving objects of a video");
  cmd->add_option("INPUT", options->input,
                  "Video file, folder of images (sorted by name), camera index or stream URL")
      ->required();
  cmd->add_option("-o,--output", options->output_dir, "Folder for the masks 00000.png, ...")
      ->required();
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
      ->check(CLI::PositiveNumber);
  cmd->add_option("--stats", options->stats_file, "Per-frame diagnostics as JSON Lines");
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
  cmd->callback([options, cmd, timeout] {
    if (cmd->count("--stats") > 0 && options->stats_file.empty()) {
      throw UsageError("--stats: the file name is empty");
    }
    if (cmd->count("--overlay") > 0 && options->overlay.empty()) {
      options->overlay = options->output_dir + "/overlay";
    }
    options->timeout = std::chrono::milliseconds(std::llround(*timeout * 1000));
    const SegmentSummary summary = runSegmentation(*options);
    if (summary.interrupted) {
      std::cerr << "movseg: interrupted after " << summary.frames
                << " frames; the files written so far are complete\n";
      throw CLI::RuntimeError(kExitInterrupted);
    }
    if (!options->quiet) std::cout << "segment: " << describeSummary(summary) << std::endl;
    const std::string problems = describeInputProblems(summary);
    if (!problems.empty()) {
      throw std::runtime_error("'" + options->input + "': " + problems +
                               "; the files written are complete");
    }
  });
}

}  // namespace movseg::cli
