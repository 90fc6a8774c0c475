// The 3-D camera path: what each motion moves, at the documented speeds, and views that always
// look forward (the painter's order of the 3-D scene relies on it).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "synth/depth_camera.h"
#include "synth/random.h"
#include "synth/synth_checks.h"

namespace movseg {
namespace {

const cv::Size kSize(320, 240);

std::vector<SynthPinhole> path(SynthCamera camera, int frames, std::uint64_t seed) {
  cv::RNG rng = synthRng(seed, SynthStream::kCamera);
  return makeDepthCameraPath(camera, frames, kSize, rng);
}

// Pan, zoom and roll turn the camera about its centre, which therefore never moves; dolly and
// forward move it without turning it, along x and z respectively, at 3–6 and 6–12 cm/frame.
TEST(SynthDepthCamera, EachMotionMovesWhatItSays) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (const SynthCamera camera :
         {SynthCamera::kPan, SynthCamera::kZoom, SynthCamera::kRotate, SynthCamera::kStatic}) {
      const std::vector<SynthPinhole> views = path(camera, 30, seed);
      const double height = -views[0].centre[1];
      EXPECT_GE(height, 1.4);
      EXPECT_LE(height, 2.0);
      for (const SynthPinhole& view : views) {
        EXPECT_EQ(view.centre, cv::Vec3d(0, -height, 0)) << synthCameraName(camera);
      }
      if (camera == SynthCamera::kStatic) {
        for (const SynthPinhole& view : views) {
          EXPECT_EQ(view.rotation, cv::Matx33d::eye());
          EXPECT_EQ(view.intrinsics, views[0].intrinsics);
        }
      }
    }
    for (const SynthCamera camera : {SynthCamera::kDolly, SynthCamera::kForward}) {
      const std::vector<SynthPinhole> views = path(camera, 30, seed);
      const int axis = camera == SynthCamera::kDolly ? 0 : 2;
      const double step = std::abs(views[1].centre[axis] - views[0].centre[axis]);
      EXPECT_GE(step, camera == SynthCamera::kDolly ? 0.03 * 0.9 : 0.06 * 0.9);
      EXPECT_LE(step, camera == SynthCamera::kDolly ? 0.06 : 0.12);
      for (const SynthPinhole& view : views) {
        EXPECT_EQ(view.rotation, cv::Matx33d::eye());
        EXPECT_EQ(view.centre[1], views[0].centre[1]);
        EXPECT_EQ(view.centre[2 - axis], views[0].centre[2 - axis]);
      }
    }
  }
}

TEST(SynthDepthCamera, ViewsAlwaysLookForward) {
  for (const SynthCamera camera : kAllCameras) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      for (const SynthPinhole& view : path(camera, 400, seed)) {
        for (const cv::Vec3d& corner : {cv::Vec3d(0, 0, 1), cv::Vec3d(319, 0, 1),
                                        cv::Vec3d(0, 239, 1), cv::Vec3d(319, 239, 1)}) {
          const cv::Vec3d ray = view.rotation.t() * (view.intrinsics.inv() * corner);
          ASSERT_GT(ray[2], 0.2 * cv::norm(ray)) << synthCameraName(camera) << " seed " << seed;
        }
      }
    }
  }
}

TEST(SynthDepthCamera, RestFocalLengthScalesWithTheWidth) {
  EXPECT_DOUBLE_EQ(restFocalLength({320, 240}), 288);
  EXPECT_DOUBLE_EQ(restFocalLength({640, 480}), 576);
}

}  // namespace
}  // namespace movseg
