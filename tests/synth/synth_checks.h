// What the tests of the synthetic scenes share (synth_test.cc, synth_depth_test.cc,
// synth_depth_camera_test.cc).
#pragma once

#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "synth/synth.h"

namespace movseg {

// Every camera of the 3-D scene (SynthScene::kDepth); the plane has the first six.
constexpr SynthCamera kAllCameras[] = {
    SynthCamera::kPan,    SynthCamera::kZoom, SynthCamera::kRotate, SynthCamera::kShake,
    SynthCamera::kStatic, SynthCamera::kMix,  SynthCamera::kDolly,  SynthCamera::kForward};

inline bool sameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Every `step`-th frame of the sequence of `options` (noiseless) against the same sequence drawn
// on black: there an object pixel is exactly a non-black pixel, so the mask can neither miss a
// visible object pixel nor claim a background or hidden one; with the background drawn, the
// mask and the object pixels are the same. Returns the object pixels seen, so that a caller can
// tell the check from one made on empty masks.
inline int expectMasksAreTheDrawnObjects(const SynthOptions& options, int step) {
  SynthOptions on_black = options;
  on_black.background = false;
  const SynthSequence scene(options), objects_only(on_black);
  int object_pixels = 0;
  for (int t = 0; t < scene.size(); t += step) {
    const SynthFrame full = scene.frame(t), bare = objects_only.frame(t);
    std::vector<cv::Mat> channels;
    cv::split(bare.frame, channels);
    const cv::Mat drawn = (channels[0] | channels[1] | channels[2]) > 0;
    EXPECT_EQ(cv::countNonZero(drawn != bare.mask), 0) << "frame " << t;
    EXPECT_TRUE(sameBytes(full.mask, bare.mask)) << "frame " << t;
    cv::Mat full_objects = cv::Mat::zeros(full.frame.size(), CV_8UC3);
    full.frame.copyTo(full_objects, full.mask);
    EXPECT_TRUE(sameBytes(full_objects, bare.frame)) << "frame " << t;
    object_pixels += cv::countNonZero(bare.mask);
  }
  return object_pixels;
}

}  // namespace movseg
