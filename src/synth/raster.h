// Exact polygon coverage, shared by everything the generator draws with a ground-truth mask: a
// pixel is either wholly covered or not at all, so masks never have partial pixels.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

struct Coverage {
  cv::Rect box;   // the polygon's bounding box within the frame; empty when it misses the frame
  cv::Mat shape;  // CV_8U, box-sized: 255 exactly on the covered pixels
};

// The pixels cv::fillPoly sets for `polygon` (frame pixel coordinates, vertices at 1/16-pixel
// precision, no anti-aliasing).
Coverage polygonCoverage(const std::vector<cv::Point2d>& polygon, cv::Size frame_size);

}  // namespace movseg
