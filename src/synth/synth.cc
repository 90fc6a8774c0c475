#include "synth/synth.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "io/atomic_write.h"
#include "synth/camera_path.h"
#include "synth/depth_scene.h"
#include "synth/objects.h"
#include "synth/random.h"
#include "synth/texture.h"

namespace movseg {
namespace {

constexpr int kMaxFrames = 100000;  // file names have five digits
constexpr int kMinSide = 16;
constexpr int kMaxSide =
    2048;  // the canvas is a few times the frame: ~400 MB to build at 2048x2048
constexpr int kMaxObjectSpeed = 30;  // px/frame at 320x240: a tenth of the frame width

const std::pair<const char*, SynthCamera> kCameraNames[] = {
    {"pan", SynthCamera::kPan},       {"zoom", SynthCamera::kZoom},
    {"rotate", SynthCamera::kRotate}, {"shake", SynthCamera::kShake},
    {"static", SynthCamera::kStatic}, {"mix", SynthCamera::kMix},
    {"dolly", SynthCamera::kDolly},   {"forward", SynthCamera::kForward},
};

const std::pair<const char*, SynthScene> kSceneNames[] = {
    {"plane", SynthScene::kPlane},
    {"depth", SynthScene::kDepth},
};

// The value called `name` in `names`; throws std::invalid_argument listing the known names.
template <typename Value, size_t N>
Value parseName(const std::pair<const char*, Value> (&names)[N], const std::string& name,
                const std::string& what) {
  std::string known;
  for (const auto& [value_name, value] : names) {
    if (name == value_name) return value;
    known += std::string(known.empty() ? "" : ", ") + value_name;
  }
  throw std::invalid_argument("unknown " + what + " '" + name + "' (known: " + known + ")");
}

template <typename Value, size_t N>
std::string nameOf(const std::pair<const char*, Value> (&names)[N], Value value,
                   const std::string& what) {
  for (const auto& [value_name, named] : names) {
    if (named == value) return value_name;
  }
  throw std::invalid_argument("unknown " + what + " value");
}

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("invalid synth option: " + what);
}

}  // namespace

void checkSynthOptions(const SynthOptions& o) {
  require(o.frames >= 1 && o.frames <= kMaxFrames, "frames must be in [1, " +
                                                       std::to_string(kMaxFrames) + "] (got " +
                                                       std::to_string(o.frames) + ")");
  const auto side_ok = [](int side) { return side >= kMinSide && side <= kMaxSide; };
  require(side_ok(o.size.width) && side_ok(o.size.height),
          "size must be within " + std::to_string(kMinSide) + "x" + std::to_string(kMinSide) +
              " .. " + std::to_string(kMaxSide) + "x" + std::to_string(kMaxSide) + " (got " +
              std::to_string(o.size.width) + "x" + std::to_string(o.size.height) + ")");
  require(o.objects >= 1 && o.objects <= 3,
          "objects must be in [1, 3] (got " + std::to_string(o.objects) + ")");
  require(o.noise_sigma >= 0 && o.noise_sigma <= 64, "noise_sigma must be in [0, 64]");
  require(o.illumination_drift >= 0 && o.illumination_drift <= 0.5,
          "illumination_drift must be in [0, 0.5]");
  require(o.object_speed_min > 0 && o.object_speed_min <= o.object_speed_max &&
              o.object_speed_max <= kMaxObjectSpeed,
          "object speeds must satisfy 0 < min <= max <= " + std::to_string(kMaxObjectSpeed) +
              " px/frame (got " + shortNumber(o.object_speed_min) + "-" +
              shortNumber(o.object_speed_max) + ")");
  const bool travels = o.camera == SynthCamera::kDolly || o.camera == SynthCamera::kForward;
  require(!travels || o.scene == SynthScene::kDepth,
          "camera " + synthCameraName(o.camera) + " needs the depth scene");
}

namespace {

// A static camera gives the identity exactly, not a rounding of H * H^-1.
cv::Matx33d frameToFrame(const cv::Matx33d& previous, const cv::Matx33d& current) {
  if (current == previous) return cv::Matx33d::eye();
  const cv::Matx33d model = current * previous.inv();
  return model * (1.0 / model(2, 2));
}

// Global gain, then Gaussian noise, then rounding to 8 bits: objects and background alike.
void expose(cv::Mat& frame, double gain, double noise_sigma, cv::RNG rng) {
  cv::Mat light;
  frame.convertTo(light, CV_32F, gain);
  if (noise_sigma > 0) {
    cv::Mat noise(light.size(), light.type());
    rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(noise_sigma));
    light += noise;
  }
  light.convertTo(frame, CV_8U);
}

nlohmann::json rowsJson(const cv::Matx33d& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back(nlohmann::json::array({matrix(r, 0), matrix(r, 1), matrix(r, 2)}));
  return rows;
}

std::string cameraLine(int t, const cv::Matx33d& model) {
  nlohmann::json line;
  line["frame"] = t;
  line["model"] = rowsJson(model);
  return line.dump();
}

std::string poseLine(int t, const SynthPinhole& pose) {
  nlohmann::json line;
  line["frame"] = t;
  line["K"] = rowsJson(pose.intrinsics);
  line["R"] = rowsJson(pose.rotation);
  line["centre"] = nlohmann::json::array({pose.centre[0], pose.centre[1], pose.centre[2]});
  return line.dump();
}

}  // namespace

struct SynthSequence::State {
  SynthOptions options;
  // H_t: background pixel -> frame t pixel, where the background is the canvas, or in the 3-D
  // scene the ground's texture.
  std::vector<cv::Matx33d> views;
  cv::Mat canvas;                    // the plane; empty without a background or in the 3-D scene
  std::vector<SynthObject> objects;  // on the plane; the 3-D scene has its own
  std::optional<DepthScene> depth;   // the 3-D scene
  Wave gain_change;                  // gain(t) - 1
};

SynthSequence::SynthSequence(const SynthOptions& options) {
  checkSynthOptions(options);
  auto state = std::make_shared<State>();
  state->options = options;
  if (options.scene == SynthScene::kDepth) {
    state->depth = makeDepthScene(options);
    for (const SynthPinhole& view : state->depth->views)
      state->views.push_back(surfaceHomography(state->depth->ground, view));
  } else {
    cv::RNG palette_rng = synthRng(options.seed, SynthStream::kPalette);
    const Palette palette = makeBackgroundPalette(palette_rng);
    cv::RNG object_rng = synthRng(options.seed, SynthStream::kObjects);
    state->objects = makeObjects(options, palette, object_rng);
    cv::RNG camera_rng = synthRng(options.seed, SynthStream::kCamera);
    CameraPath path = makeCameraPath(options.camera, options.frames, options.size, camera_rng);
    state->views = std::move(path.views);
    if (options.background) {
      cv::RNG background_rng = synthRng(options.seed, SynthStream::kBackground);
      state->canvas =
          makeBackgroundTexture(path.canvas, palette, options.size.width / 320.0, background_rng);
    }
  }
  // A slow drift: at least 150 frames per cycle.
  cv::RNG light_rng = synthRng(options.seed, SynthStream::kIllumination);
  state->gain_change.amplitude = options.illumination_drift;
  state->gain_change.period = light_rng.uniform(150.0, 300.0);
  state->gain_change.phase = light_rng.uniform(0.0, 2 * CV_PI);
  state_ = std::move(state);
}

int SynthSequence::size() const { return state_->options.frames; }

const SynthOptions& SynthSequence::options() const { return state_->options; }

SynthFrame SynthSequence::frame(int t) const {
  if (t < 0 || t >= size()) {
    throw std::out_of_range("synthetic frame " + std::to_string(t) + " outside [0, " +
                            std::to_string(size()) + ")");
  }
  const State& state = *state_;
  const SynthOptions& options = state.options;
  SynthFrame out;
  if (state.depth) {
    renderDepthFrame(*state.depth, t, options.background, out.frame, out.mask);
    out.pose = state.depth->views[t];
  } else {
    if (options.background) {
      cv::warpPerspective(state.canvas, out.frame, state.views[t], options.size, cv::INTER_LINEAR);
    } else {
      out.frame = cv::Mat::zeros(options.size, CV_8UC3);
    }
    out.mask = cv::Mat::zeros(options.size, CV_8U);
    for (const SynthObject& object : state.objects) drawObject(object, t, out.frame, out.mask);
  }
  expose(out.frame, 1 + state.gain_change.at(t), options.noise_sigma,
         synthRng(options.seed, SynthStream::kNoise, static_cast<std::uint64_t>(t)));
  out.camera = t == 0 ? cv::Matx33d::eye() : frameToFrame(state.views[t - 1], state.views[t]);
  return out;
}

// A sequence's folder: what writeSynthSequence() writes there and removeSynthSequence() removes.
constexpr char kFramesFolder[] = "/frames", kMasksFolder[] = "/masks";
constexpr char kCameraFile[] = "/camera.jsonl", kPosesFile[] = "/poses.jsonl";

void writeSynthSequence(const std::string& dir, const SynthOptions& options) {
  const SynthSequence sequence(options);
  const std::string frames_dir = dir + kFramesFolder, masks_dir = dir + kMasksFolder;
  makeOutputFolder(frames_dir);
  makeOutputFolder(masks_dir);
  std::string cameras, poses;
  for (int t = 0; t < sequence.size(); ++t) {
    const SynthFrame frame = sequence.frame(t);
    writeImageAtomic(frames_dir + "/" + frameFileName(t), frame.frame);
    writeImageAtomic(masks_dir + "/" + frameFileName(t), frame.mask);
    if (t > 0) cameras += cameraLine(t, frame.camera) + "\n";
    if (frame.pose) poses += poseLine(t, *frame.pose) + "\n";
  }
  writeTextAtomic(dir + kCameraFile, cameras);
  if (!poses.empty()) writeTextAtomic(dir + kPosesFile, poses);
}

void removeSynthSequence(const std::string& dir) {
  for (const char* folder : {kFramesFolder, kMasksFolder}) {
    for (const std::string& file : frameFilesIn(dir + folder)) std::filesystem::remove(file);
  }
  std::filesystem::remove(dir + kCameraFile);
  std::filesystem::remove(dir + kPosesFile);
}

SynthCamera parseSynthCamera(const std::string& name) {
  return parseName(kCameraNames, name, "camera motion");
}

std::string synthCameraName(SynthCamera camera) {
  return nameOf(kCameraNames, camera, "SynthCamera");
}

SynthScene parseSynthScene(const std::string& name) {
  return parseName(kSceneNames, name, "scene");
}

std::string synthSceneName(SynthScene scene) { return nameOf(kSceneNames, scene, "SynthScene"); }

}  // namespace movseg
