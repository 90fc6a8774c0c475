// Synthetic moving-camera video with exact ground truth: a textured background plane seen
// through a known homography per frame, or a 3-D static scene seen by a pinhole camera, and 1–3
// textured objects that move independently of the camera (docs/synth.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace movseg {

// What the camera sees. kPlane: one textured plane, so a homography explains every frame.
// kDepth: a ground plane, a far backdrop and posts, walls and boxes at several depths, some near
// the camera; a translating camera sees parallax.
enum class SynthScene { kPlane, kDepth };

// How the camera moves. kMix combines pan, zoom, rotation, shake and a slowly changing tilt (and,
// in the 3-D scene, dolly and forward travel). On the plane every mode sees it under a mild fixed
// tilt (perspective). kDolly (sideways travel) and kForward (travel along the view) exist only in
// the 3-D scene; there pan turns the camera about its centre, zoom changes the focal length,
// rotate rolls about the optical axis, and shake adds small translations to the turns.
enum class SynthCamera { kPan, kZoom, kRotate, kShake, kStatic, kMix, kDolly, kForward };

struct SynthOptions {
  int frames = 60;
  cv::Size size{320, 240};
  std::uint64_t seed = 1;
  SynthCamera camera = SynthCamera::kMix;
  int objects = 2;  // 1..3 independently moving objects
  // Gaussian sensor noise: standard deviation in 8-bit levels (0 = none).
  double noise_sigma = 2.5;
  // Slow global illumination change: the gain stays within 1 ± this.
  double illumination_drift = 0.04;
  // false: the objects are drawn on black (in the 3-D scene, every static surface is black but
  // still hides what is behind it). Object textures never contain black, so the ground truth can
  // then be checked pixel by pixel.
  bool background = true;
  // Object speeds in pixels per frame at 320x240 (scaled with the frame width; in the 3-D scene,
  // as a still camera sees them): each object keeps one speed drawn uniformly from [min, max].
  double object_speed_min = 1;
  double object_speed_max = 6;
  // true: object textures come from the background's texture process and palette, so that an
  // object differs from the background only by its motion (and its outline, where the textures
  // happen to differ). false: each object has its own colour, far from the palette's.
  bool camouflage = false;
  SynthScene scene = SynthScene::kPlane;
};

// The 3-D scene's camera at one frame: world point X appears at pixel K * R * (X - centre)
// (homogeneous). World axes are the camera's at rest: x right, y down, z forward, in metres; the
// ground is the plane y = 0.
struct SynthPinhole {
  cv::Matx33d intrinsics;  // K: focal length and principal point, pixels
  cv::Matx33d rotation;    // R: world axes -> camera axes
  cv::Vec3d centre;
};

struct SynthFrame {
  cv::Mat frame;  // CV_8UC3 BGR
  // CV_8U 0/255: 255 exactly where an object pixel was drawn and is visible (in the 3-D scene,
  // nearer static surfaces and the ground hide parts of objects)
  cv::Mat mask;
  // Maps frame t-1 pixel coordinates to frame t's (identity for t = 0): the background plane's
  // motion, or in the 3-D scene the ground plane's (nothing else there moves by it).
  cv::Matx33d camera;
  std::optional<SynthPinhole> pose;  // the 3-D scene's camera; none on the plane
};

// Throws std::invalid_argument naming the first option out of range: frames not in
// [1, 100000], size not within 16x16..2048x2048, objects not in [1, 3], noise_sigma not in
// [0, 64], illumination_drift not in [0, 0.5], not 0 < object_speed_min <= object_speed_max
// <= 30, or a camera motion the scene does not have (dolly, forward on the plane).
void checkSynthOptions(const SynthOptions& options);

class SynthSequence {
 public:
  // Throws std::invalid_argument as checkSynthOptions does.
  explicit SynthSequence(const SynthOptions& options);

  int size() const;
  // Random access: the result depends on the options and t only, never on earlier calls.
  // Throws std::out_of_range unless 0 <= t < size().
  SynthFrame frame(int t) const;
  const SynthOptions& options() const;

 private:
  struct State;
  std::shared_ptr<const State> state_;  // immutable once built, so copies share it
};

// Writes DIR/frames/00000.png ..., DIR/masks/00000.png ... and DIR/camera.jsonl (one line per
// t >= 1: {"frame": t, "model": [[a,b,c],[d,e,f],[g,h,i]]}, frame t's camera), and for the 3-D
// scene DIR/poses.jsonl (one line per t >= 0: {"frame": t, "K": [[...]], "R": [[...]],
// "centre": [x, y, z]}), each file atomically. Checks the options before creating anything.
// Throws std::runtime_error when a file cannot be written.
void writeSynthSequence(const std::string& dir, const SynthOptions& options);

// Removes what writeSynthSequence() writes in DIR (the numbered pictures of frames/ and masks/,
// camera.jsonl, poses.jsonl), and nothing else, so that a shorter sequence written there next
// leaves no frame of a longer one behind. Throws std::filesystem::filesystem_error when a file
// cannot be removed.
void removeSynthSequence(const std::string& dir);

// "pan", "zoom", "rotate", "shake", "static", "mix", "dolly" or "forward"; throws
// std::invalid_argument otherwise.
SynthCamera parseSynthCamera(const std::string& name);
std::string synthCameraName(SynthCamera camera);

// "plane" or "depth"; throws std::invalid_argument otherwise.
SynthScene parseSynthScene(const std::string& name);
std::string synthSceneName(SynthScene scene);

}  // namespace movseg
