#include "synth/camera_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "synth/random.h"

namespace movseg {
namespace {

// How much of each motion a camera mode has (1 = the full range of the mode of that name).
struct MotionMix {
  double pan = 0;
  double zoom = 0;
  double roll = 0;
  double shake = 0;
  bool tilt_changes = false;
};

MotionMix motionMix(SynthCamera camera) {
  switch (camera) {
    case SynthCamera::kPan:
      return {1, 0, 0, 0, false};
    case SynthCamera::kZoom:
      return {0, 1, 0, 0, false};
    case SynthCamera::kRotate:
      return {0, 0, 1, 0, false};
    case SynthCamera::kShake:
      return {0, 0, 0, 1, false};
    case SynthCamera::kStatic:
      return {0, 0, 0, 0, false};
    case SynthCamera::kMix:
      break;
    case SynthCamera::kDolly:
    case SynthCamera::kForward:
      throw std::logic_error("the plane has no " + synthCameraName(camera) + " camera");
  }
  return {0.5, 0.6, 0.6, 0.6, true};
}

// Everything that moves the camera, as waves of the frame index.
struct CameraMotion {
  cv::Point2d pan_direction{1, 0};
  Wave pan;    // canvas travel along pan_direction
  Wave weave;  // canvas travel across it
  Wave zoom;   // log of the scale
  Wave roll;   // rotation about the frame centre, radians
  // Hand-held shake: fast waves in image pixels and radians, plus per-frame uniform jitter.
  Wave shake_x[2], shake_y[2], shake_roll;
  double jitter = 0;
  double jitter_roll = 0;
  // Perspective: the last row (tilt.x, tilt.y, 1) of the homography in frame-centred
  // coordinates, a fixed part plus slow waves.
  cv::Point2d tilt;
  Wave tilt_x, tilt_y;
};

void addShake(double amount, double scale, cv::RNG& rng, CameraMotion* motion) {
  for (int i = 0; i < 2; ++i) {
    const double amplitude =
        amount * scale * (i == 0 ? rng.uniform(1.0, 1.8) : rng.uniform(0.4, 0.8));
    motion->shake_x[i] = shakeWave(amplitude, rng);
    motion->shake_y[i] = shakeWave(amplitude, rng);
  }
  motion->shake_roll = shakeWave(amount * 0.15 * kDegree, rng);
  motion->jitter = amount * 0.6 * scale;
  motion->jitter_roll = amount * 0.05 * kDegree;
}

// `half_diagonal`: tilts are sized so that the perspective changes the scale across the frame by
// at most about ±12 %, so the plane's horizon stays far outside the view.
void addTilt(bool changes, double half_diagonal, cv::RNG& rng, CameraMotion* motion) {
  const double angle = rng.uniform(0.0, 2 * CV_PI);
  const double strength = rng.uniform(0.02, 0.08) / half_diagonal;
  motion->tilt = cv::Point2d(std::cos(angle), std::sin(angle)) * strength;
  if (!changes) return;
  for (Wave* wave : {&motion->tilt_x, &motion->tilt_y}) {
    wave->amplitude = 0.03 / half_diagonal;
    wave->period = rng.uniform(150.0, 300.0);
    wave->phase = rng.uniform(0.0, 2 * CV_PI);
  }
}

CameraMotion makeMotion(SynthCamera camera, cv::Size frame_size, cv::RNG& rng) {
  const MotionMix mix = motionMix(camera);
  const double scale = frame_size.width / 320.0;
  CameraMotion motion;
  const double pan_angle = rng.uniform(0.0, 2 * CV_PI);
  motion.pan_direction = cv::Point2d(std::cos(pan_angle), std::sin(pan_angle));
  const double pan_rate = mix.pan * scale * rng.uniform(1.0, 4.0);
  motion.pan = panWave(pan_rate, rng);
  motion.weave = waveWithRate(0.3 * pan_rate, 60, 120, rng);
  motion.zoom = waveWithRate(mix.zoom * rng.uniform(0.004, 0.01), 100, 200, rng);
  motion.roll = waveWithRate(mix.roll * rng.uniform(0.2, 0.5) * kDegree, 120, 240, rng);
  addShake(mix.shake, scale, rng, &motion);
  addTilt(mix.tilt_changes, 0.5 * std::hypot(frame_size.width, frame_size.height), rng, &motion);
  return motion;
}

// H_t: rotate and scale the plane about the canvas point seen at the frame centre, shake, tilt
// about the frame centre, then move to pixel coordinates.
cv::Matx33d viewAt(const CameraMotion& motion, int t, cv::Point2d frame_centre, cv::RNG& rng) {
  const cv::Point2d normal(-motion.pan_direction.y, motion.pan_direction.x);
  const cv::Point2d seen = motion.pan.at(t) * motion.pan_direction + motion.weave.at(t) * normal;
  const double jitter_x = rng.uniform(-1.0, 1.0) * motion.jitter;
  const double jitter_y = rng.uniform(-1.0, 1.0) * motion.jitter;
  const double jitter_roll = rng.uniform(-1.0, 1.0) * motion.jitter_roll;
  const cv::Point2d shake(motion.shake_x[0].at(t) + motion.shake_x[1].at(t) + jitter_x,
                          motion.shake_y[0].at(t) + motion.shake_y[1].at(t) + jitter_y);
  const double angle = motion.roll.at(t) + motion.shake_roll.at(t) + jitter_roll;
  const double s = std::exp(motion.zoom.at(t));
  const double c = s * std::cos(angle), n = s * std::sin(angle);
  const cv::Matx33d similarity(c, -n, shake.x - (c * seen.x - n * seen.y), n, c,
                               shake.y - (n * seen.x + c * seen.y), 0, 0, 1);
  const cv::Matx33d tilt(1, 0, 0, 0, 1, 0, motion.tilt.x + motion.tilt_x.at(t),
                         motion.tilt.y + motion.tilt_y.at(t), 1);
  const cv::Matx33d to_pixels(1, 0, frame_centre.x, 0, 1, frame_centre.y, 0, 0, 1);
  return to_pixels * tilt * similarity;
}

// Moves the canvas origin to the top-left of what the frames see (their corners mapped back to
// the plane, plus a margin for interpolation) and sizes the canvas to hold all of it. The frame
// rectangle maps to a convex quadrilateral because the horizon stays outside it.
CameraPath fitCanvas(std::vector<cv::Matx33d> views, cv::Size frame_size) {
  constexpr double kMargin = 4;
  const double right = frame_size.width - 1 + kMargin, bottom = frame_size.height - 1 + kMargin;
  const cv::Vec3d corners[4] = {
      {-kMargin, -kMargin, 1}, {right, -kMargin, 1}, {-kMargin, bottom, 1}, {right, bottom, 1}};
  cv::Point2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  cv::Point2d hi = -lo;
  for (const cv::Matx33d& view : views) {
    const cv::Matx33d inverse = view.inv();
    for (const cv::Vec3d& corner : corners) {
      const cv::Vec3d p = inverse * corner;
      const cv::Point2d point(p[0] / p[2], p[1] / p[2]);
      lo = cv::Point2d(std::min(lo.x, point.x), std::min(lo.y, point.y));
      hi = cv::Point2d(std::max(hi.x, point.x), std::max(hi.y, point.y));
    }
  }
  const cv::Point2d origin(std::floor(lo.x) - 1, std::floor(lo.y) - 1);
  const cv::Matx33d from_canvas(1, 0, origin.x, 0, 1, origin.y, 0, 0, 1);
  for (cv::Matx33d& view : views) view = view * from_canvas;
  const cv::Size canvas(cvCeil(hi.x - origin.x) + 2, cvCeil(hi.y - origin.y) + 2);
  return {std::move(views), canvas};
}

}  // namespace

CameraPath makeCameraPath(SynthCamera camera, int frames, cv::Size frame_size, cv::RNG& rng) {
  const CameraMotion motion = makeMotion(camera, frame_size, rng);
  const cv::Point2d frame_centre((frame_size.width - 1) / 2.0, (frame_size.height - 1) / 2.0);
  std::vector<cv::Matx33d> views;
  views.reserve(frames);
  for (int t = 0; t < frames; ++t) views.push_back(viewAt(motion, t, frame_centre, rng));
  return fitCanvas(std::move(views), frame_size);
}

}  // namespace movseg
