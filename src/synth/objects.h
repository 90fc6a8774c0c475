// The synthetic moving objects: textured shapes moving in image coordinates, independently of
// the camera, bouncing inside a box around the frame that lets some of them leave and return.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "synth/synth.h"
#include "synth/texture.h"

namespace movseg {

struct SynthObject {
  std::vector<cv::Point2d> outline;  // ellipse, polygon or blob around the object's centre
  cv::Mat texture;                   // CV_8UC3, square, its centre on the object's centre
  std::vector<cv::Point2d> centre;   // per frame, image pixel coordinates
  std::vector<double> angle;         // per frame, radians
};

// `options.objects` objects for the clip: each covers 5 % to 25 % / sqrt(count) of the frame
// and moves at a speed within the options' range (px/frame at 320x240, scaled with the frame
// width), along gently curving paths while turning slowly. Textured as options.camouflage says.
std::vector<SynthObject> makeObjects(const SynthOptions& options, const Palette& palette,
                                     cv::RNG& rng);

// Draws the object as it is at frame t into `frame` (CV_8UC3) and sets 255 in `mask` (CV_8U)
// on exactly the pixels it drew.
void drawObject(const SynthObject& object, int t, cv::Mat& frame, cv::Mat& mask);

}  // namespace movseg
