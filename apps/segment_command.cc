// movseg segment INPUT -o OUTDIR [--overlay [PATH]] [--debug] [--static] [--max-frames N] ...
#include <iostream>
#include <memory>

#include "commands.h"
#include "methods/method.h"
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
  cmd->add_flag("--debug", options->debug, "Write each stage's pictures to OUTDIR/debug/<stage>/");
  cmd->add_option("--max-frames", options->max_frames, "Stop after N frames")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--stats", options->stats_file, "Per-frame diagnostics as JSON Lines");
  cmd->add_option("--method", options->method, "Segmentation method")
      ->check(CLI::IsMember(methodNames()))
      ->capture_default_str();
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
      throw std::runtime_error("interrupted");
    }
    if (!options->quiet) std::cout << "segment: " << describeSummary(summary) << "\n";
  });
}

}  // namespace movseg::cli
