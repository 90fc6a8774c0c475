// movseg segment INPUT -o OUTDIR [--overlay [PATH]] [--show] [--debug] [--static] ...
#include <iostream>
#include <memory>

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
                  "Overlay pictures: a folder (PNG frames) or a video file (.mp4, .avi, .mkv); "
                  "without a value, OUTDIR/overlay/")
      ->expected(0, 1)
      ->default_str("");
  cmd->add_flag("--show", options->show,
                "Show the overlay in a live window (needs a display; q or Esc stops)");
  cmd->add_flag("--debug", options->debug, "Write each stage's pictures to OUTDIR/debug/<stage>/");
  cmd->add_option("--max-frames", options->max_frames, "Stop after N frames")
      ->check(kNotNegative);
  cmd->add_option("--stats", options->stats_file, "Per-frame diagnostics as JSON Lines");
  cmd->add_flag("-q,--quiet", options->quiet, "No progress bar and no summary");
  addParamsOptions(cmd, &options->params);
  cmd->callback([options, cmd] {
    if (cmd->count("--overlay") > 0 && options->overlay.empty()) {
      options->overlay = options->output_dir + "/overlay";
    }
    const SegmentSummary summary = runSegmentation(*options);
    if (summary.interrupted) {
      std::cerr << "movseg: interrupted after " << summary.frames
                << " frames; the files written so far are complete\n";
      throw CLI::RuntimeError(130);  // 128 + SIGINT, the shell's code for a run stopped by Ctrl-C
    }
    if (summary.stream_ended) {
      std::cerr << "movseg: '" << options->input << "' gave no more frames after " << summary.frames
                << " (the stream ended or stalled); the masks written so far are complete\n";
    }
    if (!options->quiet) std::cout << "segment: " << describeSummary(summary) << "\n";
  });
}

}  // namespace movseg::cli
