#include "synth/depth_camera.h"

#include <algorithm>
#include <cmath>

#include "synth/random.h"

namespace movseg {
namespace {

// The rest focal length at 320x240: turning by one pixel's angle there moves the frame centre by
// a pixel, which is how the plane's pan and shake, in pixels, become angles here.
constexpr double kFocalAt320 = 0.9 * 320;

// How much of each motion a camera mode has (1 = the full range of the mode of that name).
struct DepthMotionMix {
  double dolly = 0;
  double forward = 0;
  double pan = 0;
  double zoom = 0;
  double roll = 0;
  double shake = 0;
};

DepthMotionMix depthMotionMix(SynthCamera camera) {
  switch (camera) {
    case SynthCamera::kDolly:
      return {1, 0, 0, 0, 0, 0};
    case SynthCamera::kForward:
      return {0, 1, 0, 0, 0, 0};
    case SynthCamera::kPan:
      return {0, 0, 1, 0, 0, 0};
    case SynthCamera::kZoom:
      return {0, 0, 0, 1, 0, 0};
    case SynthCamera::kRotate:
      return {0, 0, 0, 0, 1, 0};
    case SynthCamera::kShake:
      return {0, 0, 0, 0, 0, 1};
    case SynthCamera::kStatic:
      return {};
    case SynthCamera::kMix:
      break;
  }
  return {0.5, 0.4, 0.5, 0.6, 0.6, 0.6};
}

// Everything that moves the camera, as waves of the frame index. Angles in radians, travels in
// metres.
struct DepthMotion {
  double height = 0;  // of the rest centre above the ground
  Wave sideways, forward;
  Wave yaw, pitch, roll;
  Wave zoom;  // log of the focal length's scale
  // Hand-held shake: fast waves, plus per-frame uniform jitter.
  Wave shake_yaw[2], shake_pitch[2], shake_roll, shake_x, shake_y;
  double jitter_angle = 0, jitter_roll = 0, jitter_travel = 0;
};

double randomSign(cv::RNG& rng) { return rng.uniform(0, 2) == 0 ? -1.0 : 1.0; }

// The plane's shake (camera_path.cc) in angles, plus a small translation: a hand holding the
// camera also moves it.
void addShake(double amount, cv::RNG& rng, DepthMotion* motion) {
  for (int i = 0; i < 2; ++i) {
    const double pixels = i == 0 ? rng.uniform(1.0, 1.8) : rng.uniform(0.4, 0.8);
    motion->shake_yaw[i] = shakeWave(amount * pixels / kFocalAt320, rng);
    motion->shake_pitch[i] = shakeWave(amount * pixels / kFocalAt320, rng);
  }
  motion->shake_roll = shakeWave(amount * 0.15 * kDegree, rng);
  motion->shake_x = shakeWave(amount * rng.uniform(0.005, 0.015), rng);
  motion->shake_y = shakeWave(amount * rng.uniform(0.005, 0.015), rng);
  motion->jitter_angle = amount * 0.6 / kFocalAt320;
  motion->jitter_roll = amount * 0.05 * kDegree;
  motion->jitter_travel = amount * 0.003;
}

DepthMotion makeMotion(SynthCamera camera, cv::RNG& rng) {
  const DepthMotionMix mix = depthMotionMix(camera);
  DepthMotion motion;
  motion.height = rng.uniform(1.4, 2.0);
  // One draw per statement: the order of the operands of * is unspecified.
  const double sideways_sign = randomSign(rng);
  const double sideways_rate = sideways_sign * mix.dolly * rng.uniform(0.03, 0.06);
  // Travels sweep back more slowly than pans: over a 60-frame clip they keep going one way.
  motion.sideways = sweepWave(sideways_rate, 400, 700, rng);
  motion.forward = sweepWave(mix.forward * rng.uniform(0.06, 0.12), 400, 700, rng);
  const double pan_sign = randomSign(rng);
  const double pan_rate = pan_sign * mix.pan * rng.uniform(1.0, 4.0) / kFocalAt320;
  motion.yaw = panWave(pan_rate, rng);
  motion.pitch = waveWithRate(0.3 * pan_rate, 60, 120, rng);
  motion.roll = waveWithRate(mix.roll * rng.uniform(0.2, 0.5) * kDegree, 120, 240, rng);
  motion.zoom = waveWithRate(mix.zoom * rng.uniform(0.004, 0.01), 100, 200, rng);
  addShake(mix.shake, rng, &motion);
  return motion;
}

cv::Matx33d rotationAboutX(double a) {
  return {1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a)};
}
cv::Matx33d rotationAboutY(double a) {
  return {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)};
}
cv::Matx33d rotationAboutZ(double a) {
  return {std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1};
}

// Camera to world: roll about the optical axis, then pitch (up for positive angles), then yaw
// about the vertical (to the right for positive angles).
SynthPinhole viewAt(const DepthMotion& motion, int t, cv::Size frame_size, cv::RNG& rng) {
  const auto jitter = [&rng](double amount) { return rng.uniform(-1.0, 1.0) * amount; };
  const double yaw = motion.yaw.at(t) + motion.shake_yaw[0].at(t) + motion.shake_yaw[1].at(t) +
                     jitter(motion.jitter_angle);
  const double pitch = motion.pitch.at(t) + motion.shake_pitch[0].at(t) +
                       motion.shake_pitch[1].at(t) + jitter(motion.jitter_angle);
  const double roll = motion.roll.at(t) + motion.shake_roll.at(t) + jitter(motion.jitter_roll);
  const double x = motion.sideways.at(t) + motion.shake_x.at(t) + jitter(motion.jitter_travel);
  const double y = motion.shake_y.at(t) + jitter(motion.jitter_travel) - motion.height;
  const double focal = restFocalLength(frame_size) * std::exp(motion.zoom.at(t));
  SynthPinhole view;
  view.intrinsics = cv::Matx33d(focal, 0, (frame_size.width - 1) / 2.0, 0, focal,
                                (frame_size.height - 1) / 2.0, 0, 0, 1);
  view.rotation = (rotationAboutY(yaw) * rotationAboutX(pitch) * rotationAboutZ(roll)).t();
  view.centre = cv::Vec3d(x, y, motion.forward.at(t));
  return view;
}

}  // namespace

double restFocalLength(cv::Size frame_size) {
  return 0.9 * std::max(frame_size.width, frame_size.height);
}

std::vector<SynthPinhole> makeDepthCameraPath(SynthCamera camera, int frames, cv::Size frame_size,
                                              cv::RNG& rng) {
  const DepthMotion motion = makeMotion(camera, rng);
  std::vector<SynthPinhole> views;
  views.reserve(frames);
  for (int t = 0; t < frames; ++t) views.push_back(viewAt(motion, t, frame_size, rng));
  return views;
}

}  // namespace movseg
