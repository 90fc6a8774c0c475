// §3.1 feature points: corners plus edge points, spread over the whole image (ref. [15]), and
// the per-frame data the tracking needs.
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

// A frame as §3.1 sees it: 8-bit grey at the alignment scale, its features, and its LK pyramid.
struct AlignmentFrame {
  cv::Mat grey;
  std::vector<cv::Point2f> features;  // detectFeatures(grey): they serve §3.2 in every mode
  std::vector<cv::Mat> pyramid;       // empty with a static camera or a frame too small to track
};

AlignmentFrame prepareAlignment(const cv::Mat& grey, const Params& params);

}  // namespace movseg
