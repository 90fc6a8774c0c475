// Textures of the synthetic scene: a background plane busy enough for corner and edge features
// everywhere, and object textures whose colours differ from it on average but not everywhere.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Colours (BGR, 8-bit units) the background's shapes are drawn around.
using Palette = std::vector<cv::Vec3d>;

Palette makeBackgroundPalette(cv::RNG& rng);

// CV_8UC3 background: smooth noise at several scales, a dense scatter of shapes and lines in
// colours around the palette's, and fine grain. `scale` (frame width / 320) sizes the details
// like the frame.
cv::Mat makeBackgroundTexture(cv::Size size, const Palette& palette, double scale, cv::RNG& rng);

// The farthest from the palette of a few random colours.
cv::Vec3d pickObjectColour(const Palette& palette, cv::RNG& rng);

// side x side CV_8UC3 texture around `colour`: smooth noise plus stripes or spots of a second
// colour. Every channel of every pixel is at least 16, so an object is never black.
cv::Mat makeObjectTexture(int side, const cv::Vec3d& colour, double scale, cv::RNG& rng);

}  // namespace movseg
