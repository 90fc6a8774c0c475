#include "cut/geodesic.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core/hal/hal.hpp>

namespace movseg {
namespace {

// Step costs between each pixel and its neighbour at (dx, dy), from the colour's three planes;
// the last column/row that has no such neighbour is left at 0 and never read. On planes the
// row loop vectorises, and OpenCV's vectorised sqrt takes a row's roots (the same values as
// std::sqrt per pixel, in under half the instructions of the per-pixel loop on Vec3f).
cv::Mat stepCosts(const cv::Mat (&planes)[3], int dx, int dy, double gamma, double length) {
  const cv::Size size = planes[0].size();
  cv::Mat cost(size, CV_32F, cv::Scalar(0));
  const float g2 = static_cast<float>(gamma * gamma), l2 = static_cast<float>(length * length);
  const int first = std::max(0, -dx), end = std::min(size.width, size.width - dx);
  for (int y = 0; y + dy < size.height; ++y) {
    const float *b = planes[0].ptr<float>(y), *g = planes[1].ptr<float>(y),
                *r = planes[2].ptr<float>(y);
    const float *nb = planes[0].ptr<float>(y + dy), *ng = planes[1].ptr<float>(y + dy),
                *nr = planes[2].ptr<float>(y + dy);
    float* out = cost.ptr<float>(y);
    for (int x = first; x < end; ++x) {
      const float db = b[x] - nb[x + dx], dg = g[x] - ng[x + dx], dr = r[x] - nr[x + dx];
      out[x] = l2 + g2 * (db * db + dg * dg + dr * dr);
    }
    if (end > first) cv::hal::sqrt32f(out + first, out + first, end - first);
  }
  return cost;
}

}  // namespace

GeodesicGrid::GeodesicGrid(const cv::Mat& colour, double gamma) : size_(colour.size()) {
  CV_Assert(colour.type() == CV_32FC3);
  cv::Mat planes[3];
  cv::split(colour, planes);
  right_ = stepCosts(planes, 1, 0, gamma, 1.0);
  down_left_ = stepCosts(planes, -1, 1, gamma, std::sqrt(2.0));
  down_ = stepCosts(planes, 0, 1, gamma, 1.0);
  down_right_ = stepCosts(planes, 1, 1, gamma, std::sqrt(2.0));
}

cv::Mat GeodesicGrid::distanceFrom(const std::vector<cv::Point>& seeds, int max_sweeps) const {
  cv::Mat distance(size_, CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
  if (seeds.empty()) return distance;
  for (const cv::Point& s : seeds) distance.at<float>(s) = 0.f;
  for (int i = 0; i < max_sweeps; ++i) {
    const bool forward_changed = forwardPass(distance);
    const bool backward_changed = backwardPass(distance);
    if (i > 0 && !forward_changed && !backward_changed) break;
  }
  return distance;
}

namespace {

// d[x] = min(d[x], from[x + df] + step[x + ds]) for x in [first, end); whether any d fell.
// The flag is a local and there is no branch, so that GCC vectorises the loop.
bool relaxRow(float* d, const float* from, int df, const float* step, int ds, int first,
              int end) {
  int fell = 0;
  for (int x = first; x < end; ++x) {
    const float candidate = from[x + df] + step[x + ds];
    fell |= candidate < d[x];
    d[x] = std::min(d[x], candidate);
  }
  return fell != 0;
}

// The same from the row's own neighbour on the side already visited (x - dir), one pixel
// after the other: each pixel's result feeds the next.
bool relaxAlongRow(float* d, const float* right, int dir, int w) {
  if (w < 2) return false;
  int fell = 0;
  const int first = dir > 0 ? 1 : w - 2, end = dir > 0 ? w : -1;
  for (int x = first; x != end; x += dir) {
    // The step between x and x - dir is stored at the left one of the two.
    const float candidate = d[x - dir] + right[dir > 0 ? x - 1 : x];
    fell |= candidate < d[x];
    d[x] = std::min(d[x], candidate);
  }
  return fell != 0;
}

}  // namespace

// Relaxes each pixel from its already visited neighbours: up, up-left, up-right, left.
bool GeodesicGrid::forwardPass(cv::Mat& distance) const {
  const int w = size_.width;
  bool changed = false;
  for (int y = 0; y < size_.height; ++y) {
    float* d = distance.ptr<float>(y);
    if (y > 0) {
      const float* up = distance.ptr<float>(y - 1);
      changed |= relaxRow(d, up, 0, down_.ptr<float>(y - 1), 0, 0, w);
      changed |= relaxRow(d, up, -1, down_right_.ptr<float>(y - 1), -1, 1, w);
      changed |= relaxRow(d, up, 1, down_left_.ptr<float>(y - 1), 1, 0, w - 1);
    }
    changed |= relaxAlongRow(d, right_.ptr<float>(y), 1, w);
  }
  return changed;
}

// Relaxes each pixel from down, down-right, down-left, right.
bool GeodesicGrid::backwardPass(cv::Mat& distance) const {
  const int w = size_.width;
  bool changed = false;
  for (int y = size_.height - 1; y >= 0; --y) {
    float* d = distance.ptr<float>(y);
    if (y + 1 < size_.height) {
      const float* below = distance.ptr<float>(y + 1);
      changed |= relaxRow(d, below, 0, down_.ptr<float>(y), 0, 0, w);
      changed |= relaxRow(d, below, 1, down_right_.ptr<float>(y), 0, 0, w - 1);
      changed |= relaxRow(d, below, -1, down_left_.ptr<float>(y), 0, 1, w);
    }
    changed |= relaxAlongRow(d, right_.ptr<float>(y), -1, w);
  }
  return changed;
}

}  // namespace movseg
