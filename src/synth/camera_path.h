// The synthetic camera: for each frame t a homography H_t from background-plane (canvas) pixel
// coordinates to frame t's pixel coordinates. Frame t-1 maps to frame t by H_t * H_{t-1}^-1.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "synth/synth.h"

namespace movseg {

struct CameraPath {
  std::vector<cv::Matx33d> views;  // H_t for every frame
  cv::Size canvas;                 // every frame sees only canvas pixels, with a margin
};

// Motion magnitudes at 320x240, scaled with the frame width: pan 1–4 px/frame, rotation up to
// 0.5°/frame, zoom up to 1 %/frame, shake a few pixels. All motions are bounded waves, so the
// canvas does not grow with the number of frames.
CameraPath makeCameraPath(SynthCamera camera, int frames, cv::Size frame_size, cv::RNG& rng);

}  // namespace movseg
