// movseg demo: what `make run` runs. Writes a synthetic moving-camera clip with exact ground
// truth, segments it (the default method unless --method says otherwise), scores the masks and
// prints the result.
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "eval/dataset.h"
#include "params_options.h"
#include "segment_run.h"
#include "synth/synth.h"

namespace movseg::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string dir;         // -o; without it, movseg-demo in the folder for temporary files
  bool overwrite = false;  // true for the default folder: the demo's own, each run replaces it
  SynthOptions synth;
  Params params;
};

// The default folder, replaced on each run, sits at a name anyone may take in a shared /tmp: a
// link there, or a folder of another user's, would have the demo replace files elsewhere. It is
// made first (a name taken between a check and the writes would pass the check), and then, in a
// sticky /tmp, nobody else can move it.
std::string ownDefaultFolder(const fs::path& folder) {
  struct stat status {};
  if ((::mkdir(folder.c_str(), 0700) != 0 && errno != EEXIST) ||
      lstat(folder.c_str(), &status) != 0 || !S_ISDIR(status.st_mode) ||
      status.st_uid != geteuid()) {
    throw std::runtime_error("'" + folder.string() +
                             "' is a link, a file or another user's folder, which the demo "
                             "would replace: remove it or give -o");
  }
  return folder.string();
}

void runDemo(const DemoOptions& options) {
  claimSequenceFolder(options.dir, options.overwrite, {"overlay"});
  writeSynthSequence(options.dir, options.synth);
  std::cout << "demo: wrote " << options.synth.frames << " synthetic frames ("
            << options.synth.size.width << "x" << options.synth.size.height << ", camera "
            << synthCameraName(options.synth.camera) << ", " << options.synth.objects
            << " moving objects) to " << options.dir << "\n";

  SegmentOptions segment;
  segment.input = (fs::path(options.dir) / "frames").string();
  segment.output_dir = (fs::path(options.dir) / "segmented").string();
  segment.overlay = (fs::path(options.dir) / "overlay").string();
  segment.params = options.params;
  segment.overwrite = true;  // the folder is the demo's, claimed above
  const SegmentSummary summary = runSegmentation(segment);
  throwIfInterrupted(summary.frames, summary.interrupted);
  std::cout << "segment: " << describeSummary(summary) << "\n";

  const std::vector<GtSequence> truth = loadGroundTruth(options.dir, GtFormat::kDavis);
  const ScoreSummary score = summarize(scoreSequence(truth.front(), segment.output_dir));
  std::printf("demo: J %.3f, F %.3f, error rate %.2f %% over %d frames (the first has no "
              "motion and is not counted)\n",
              score.j, score.f, score.error_rate, score.frames);
  std::cout << "demo: masks in " << segment.output_dir << ", overlays in " << segment.overlay
            << "\n";
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  options->synth.frames = 90;
  CLI::App* cmd = app.add_subcommand(
      "demo", "Generate a synthetic moving-camera clip, segment it, print the result");
  cmd->add_option(
         "-o,--output", options->dir,
         "Folder for the clip, masks and overlays (default: movseg-demo in $TMPDIR or /tmp, "
         "replaced on each run)");
  cmd->add_flag("--overwrite", options->overwrite, kOverwriteSequenceHelp);
  cmd->add_option("--frames", options->synth.frames,
                  "Frames of the clip, at least 2 (the first has no motion to score)")
      ->capture_default_str();
  cmd->add_option("--clip-seed", options->synth.seed, "Seed of the synthetic clip")
      ->check(kSeed)
      ->capture_default_str();
  addParamsOptions(cmd, &options->params);
  cmd->callback([options, cmd] {
    refuseEmptyNames(*cmd, {"-o"});
    interpretOptions([&] {
      checkSynthOptions(options->synth);
      if (options->synth.frames < 2) {
        throw std::invalid_argument(
            "--frames must be at least 2: the first frame has no motion "
            "and is not scored (got " +
            std::to_string(options->synth.frames) + ")");
      }
    });
    if (cmd->count("-o") == 0) {
      options->dir = ownDefaultFolder(temporaryFolder() / "movseg-demo");
      options->overwrite = true;
    }
    runDemo(*options);
  });
}

}  // namespace movseg::cli
