// movseg synth -o DIR [--frames N] [--size WxH] [--seed S] [--scene NAME] [--camera NAME] ...
#include <iostream>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "commands.h"
#include "params_options.h"
#include "synth/synth.h"

namespace movseg::cli {
namespace {

struct SynthCommandOptions {
  std::string output_dir;
  std::string size = "320x240";
  std::string camera = "mix";
  std::string scene = "plane";
  std::string object_speed = "1-6";
  bool overwrite = false;
  SynthOptions synth;
};

// "MIN-MAX" or a single speed "S" (= "S-S"), px/frame; the generator checks the range itself.
std::pair<double, double> parseSpeedRange(const std::string& text) {
  const std::regex pattern(R"((\d+(?:\.\d*)?)(?:-(\d+(?:\.\d*)?))?)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw std::invalid_argument("--object-speed must be MIN-MAX or SPEED in px/frame, e.g. 1-3.5 "
                                "(got '" + text + "')");
  }
  const double lo = std::stod(match[1]);
  return {lo, match[2].matched ? std::stod(match[2]) : lo};
}

std::string describe(const SynthOptions& o, const std::string& dir) {
  const std::string scene =
      o.scene == SynthScene::kPlane ? "" : ", scene " + synthSceneName(o.scene);
  return "wrote " + std::to_string(o.frames) + " frames (" + std::to_string(o.size.width) + "x" +
         std::to_string(o.size.height) + scene + ", camera " + synthCameraName(o.camera) + ", " +
         std::to_string(o.objects) + (o.objects == 1 ? " object" : " objects") + ", seed " +
         std::to_string(o.seed) + ") to " + dir;
}

}  // namespace

void addSynthCommand(CLI::App& app) {
  auto options = std::make_shared<SynthCommandOptions>();
  SynthOptions& synth = options->synth;
  CLI::App* cmd = app.add_subcommand(
      "synth", "Write a deterministic synthetic sequence with exact ground truth");
  cmd->add_option("-o,--output", options->output_dir,
                  "Folder for frames/, masks/ (00000.png, ...), camera.jsonl (and for the depth "
                  "scene poses.jsonl)")
      ->required();
  cmd->add_option("--frames", synth.frames, "Number of frames")->capture_default_str();
  cmd->add_option("--size", options->size, "Frame size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--seed", synth.seed, "Seed: equal seeds give identical files")
      ->check(kSeed)
      ->capture_default_str();
  cmd->add_option("--scene", options->scene,
                  "plane (one textured plane) or depth (3-D: ground, near and far posts, "
                  "walls, boxes)")
      ->capture_default_str();
  cmd->add_option("--camera", options->camera,
                  "Camera motion: pan, zoom, rotate, shake, static, mix; depth scene also "
                  "dolly, forward")
      ->capture_default_str();
  cmd->add_option("--objects", synth.objects, "Independently moving objects (1-3)")
      ->capture_default_str();
  cmd->add_option("--noise", synth.noise_sigma, "Sensor noise sigma, 8-bit levels")
      ->capture_default_str();
  cmd->add_option("--illumination", synth.illumination_drift,
                  "Slow global gain change: the gain stays within 1 +- this")
      ->capture_default_str();
  cmd->add_option("--object-speed", options->object_speed,
                  "Object speed range MIN-MAX, px/frame at 320x240 (scaled with the width)")
      ->capture_default_str();
  cmd->add_flag("--camouflage", synth.camouflage,
                "Texture the objects like the background: only their motion gives them away");
  cmd->add_flag("--overwrite", options->overwrite, kOverwriteSequenceHelp);
  cmd->callback([options, cmd] {
    refuseEmptyNames(*cmd, {"-o"});
    interpretOptions([&] {
      options->synth.size = parseSize("--size", options->size);
      options->synth.camera = parseSynthCamera(options->camera);
      options->synth.scene = parseSynthScene(options->scene);
      std::tie(options->synth.object_speed_min, options->synth.object_speed_max) =
          parseSpeedRange(options->object_speed);
      checkSynthOptions(options->synth);
    });
    claimSequenceFolder(options->output_dir, options->overwrite);
    writeSynthSequence(options->output_dir, options->synth);
    std::cout << "synth: " << describe(options->synth, options->output_dir) << "\n";
  });
}

}  // namespace movseg::cli
