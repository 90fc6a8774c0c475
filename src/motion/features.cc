#include "motion/features.h"

#include <algorithm>
#include <cstdlib>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace movseg {
namespace {

// |gx| + |gy| of the 3x3 Sobel on 8-bit grey; below this a cell has no edge worth tracking.
constexpr int kMinEdgeGradient = 60;

// One pass over the gradient magnitude keeps each cell's strongest pixel (a per-cell
// cv::minMaxLoc costs more in call overhead than the scan itself at small cells).
void addEdgePoints(const cv::Mat& grey, int cell, int margin, std::vector<cv::Point2f>* points) {
  cv::Mat gx, gy;
  cv::Sobel(grey, gx, CV_16S, 1, 0);
  cv::Sobel(grey, gy, CV_16S, 0, 1);
  const cv::Rect inner(margin, margin, grey.cols - 2 * margin, grey.rows - 2 * margin);
  const int cells_x = (inner.width + cell - 1) / cell, cells_y = (inner.height + cell - 1) / cell;
  std::vector<int> best(static_cast<size_t>(cells_x) * cells_y, kMinEdgeGradient - 1);
  std::vector<cv::Point> at(best.size());
  for (int y = inner.y; y < inner.br().y; ++y) {
    const short* row_x = gx.ptr<short>(y);
    const short* row_y = gy.ptr<short>(y);
    const size_t cell_row = static_cast<size_t>((y - inner.y) / cell) * cells_x;
    // Cell by cell along the row (no division per pixel); each cell's pixels in raster order.
    for (int x0 = inner.x, c = 0; x0 < inner.br().x; x0 += cell, ++c) {
      const int x1 = std::min(x0 + cell, inner.br().x);
      int& cell_best = best[cell_row + static_cast<size_t>(c)];
      for (int x = x0; x < x1; ++x) {
        const int magnitude = std::abs(row_x[x]) + std::abs(row_y[x]);
        if (magnitude > cell_best) {
          cell_best = magnitude;
          at[cell_row + static_cast<size_t>(c)] = {x, y};
        }
      }
    }
  }
  for (size_t c = 0; c < best.size(); ++c) {
    if (best[c] >= kMinEdgeGradient) points->emplace_back(at[c]);
  }
}

}  // namespace

std::vector<cv::Point2f> detectFeatures(const cv::Mat& grey, const Params& params) {
  std::vector<cv::Point2f> points;
  const int margin = params.zncc_window / 2 + 1;
  if (grey.cols <= 2 * margin || grey.rows <= 2 * margin) return points;

  cv::Mat mask = cv::Mat::zeros(grey.size(), CV_8U);
  mask(cv::Rect(margin, margin, grey.cols - 2 * margin, grey.rows - 2 * margin)).setTo(255);
  const double min_distance = std::max(1, params.edge_cell / 2);
  cv::goodFeaturesToTrack(grey, points, params.max_corners, 0.01, min_distance, mask);
  addEdgePoints(grey, params.edge_cell, margin, &points);
  return points;
}

AlignmentFrame prepareAlignment(const cv::Mat& grey, const Params& params) {
  AlignmentFrame frame;
  frame.grey = grey;
  frame.features = detectFeatures(grey, params);
  // LK needs a window's worth of pixels at the base level; smaller frames are not tracked.
  const bool trackable = std::min(grey.cols, grey.rows) >= params.lk_window + 1;
  if (!params.static_camera && trackable) {
    const cv::Size window(params.lk_window, params.lk_window);
    cv::buildOpticalFlowPyramid(grey, frame.pyramid, window, params.lk_levels, true);
  }
  return frame;
}

}  // namespace movseg
