// The camera of the 3-D scene: a pinhole with a real pose for each frame. World axes are the
// camera's at rest: x right, y down, z forward, in metres; the ground is the plane y = 0.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "synth/synth.h"

namespace movseg {

// The focal length at rest, in pixels: 0.9 x the frame's longer side (a 58° field of view along
// it). The width alone made a tall portrait frame see sideways (a 20:1 one over 170° high).
double restFocalLength(cv::Size frame_size);

// One view per frame. The camera starts level at 1.4–2 m above the ground, at x = z = 0 (the rest
// pose), and moves as `camera` says. Magnitudes, the same at every frame size (so pixel motions
// scale with the frame width): dolly 3–6 cm/frame sideways, forward 6–12 cm/frame, pan (turn about
// the vertical axis, with a slight tilt) as fast as the plane's pan of 1–4 px/frame at 320x240,
// zoom up to 1 %/frame of focal length, rotate (roll) up to 0.5°/frame, shake the plane's
// hand-held turns plus 0.5–1.5 cm of sideways and vertical jiggle. Travels and turns are bounded
// waves like the plane's, so the scene the clip sees stays bounded however long the clip.
std::vector<SynthPinhole> makeDepthCameraPath(SynthCamera camera, int frames, cv::Size frame_size,
                                              cv::RNG& rng);

}  // namespace movseg
