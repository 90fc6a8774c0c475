// §3.1 feature points: corners plus edge points, spread over the whole image (ref. [15]).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

// Shi–Tomasi corners (at most params.max_corners, at least edge_cell / 2 apart) plus, for every
// edge_cell x edge_cell cell, the pixel of strongest gradient when it is a clear edge. The grid
// keeps one textured region from taking every point. Points keep a margin from the border so
// that their ZNCC window (eq. 2) fits.
std::vector<cv::Point2f> detectFeatures(const cv::Mat& grey, const Params& params);

}  // namespace movseg
