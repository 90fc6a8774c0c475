#include "cut/geodesic.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace movseg {
namespace {

// Step costs between each pixel and its neighbour at (dx, dy); the last column/row that has no
// such neighbour is left at 0 and never read.
cv::Mat stepCosts(const cv::Mat& colour, int dx, int dy, double gamma, double length) {
  cv::Mat cost(colour.size(), CV_32F, cv::Scalar(0));
  const float g2 = static_cast<float>(gamma * gamma), l2 = static_cast<float>(length * length);
  for (int y = 0; y + dy < colour.rows; ++y) {
    const auto* row = colour.ptr<cv::Vec3f>(y);
    const auto* next = colour.ptr<cv::Vec3f>(y + dy);
    float* out = cost.ptr<float>(y);
    for (int x = std::max(0, -dx); x < colour.cols && x + dx < colour.cols; ++x) {
      const cv::Vec3f d = row[x] - next[x + dx];
      out[x] = std::sqrt(l2 + g2 * d.dot(d));
    }
  }
  return cost;
}

}  // namespace

GeodesicGrid::GeodesicGrid(const cv::Mat& colour, double gamma) : size_(colour.size()) {
  right_ = stepCosts(colour, 1, 0, gamma, 1.0);
  down_left_ = stepCosts(colour, -1, 1, gamma, std::sqrt(2.0));
  down_ = stepCosts(colour, 0, 1, gamma, 1.0);
  down_right_ = stepCosts(colour, 1, 1, gamma, std::sqrt(2.0));
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

// d = min(d, candidate), noting a decrease; branch-free so the row loops vectorise.
inline void relax(float& d, float candidate, bool* changed) {
  *changed |= candidate < d;
  d = std::min(d, candidate);
}

}  // namespace

// Relaxes each pixel from its already visited neighbours: left, up-left, up, up-right.
bool GeodesicGrid::forwardPass(cv::Mat& distance) const {
  const int w = size_.width;
  bool changed = false;
  for (int y = 0; y < size_.height; ++y) {
    float* d = distance.ptr<float>(y);
    const float* right = right_.ptr<float>(y);
    if (y > 0) {
      const float* up = distance.ptr<float>(y - 1);
      const float* down = down_.ptr<float>(y - 1);
      const float* down_left = down_left_.ptr<float>(y - 1);
      const float* down_right = down_right_.ptr<float>(y - 1);
      for (int x = 0; x < w; ++x) relax(d[x], up[x] + down[x], &changed);
      for (int x = 1; x < w; ++x) relax(d[x], up[x - 1] + down_right[x - 1], &changed);
      for (int x = 0; x + 1 < w; ++x) relax(d[x], up[x + 1] + down_left[x + 1], &changed);
    }
    for (int x = 1; x < w; ++x) relax(d[x], d[x - 1] + right[x - 1], &changed);
  }
  return changed;
}

// Relaxes each pixel from right, down-right, down, down-left.
bool GeodesicGrid::backwardPass(cv::Mat& distance) const {
  const int w = size_.width;
  bool changed = false;
  for (int y = size_.height - 1; y >= 0; --y) {
    float* d = distance.ptr<float>(y);
    const float* right = right_.ptr<float>(y);
    if (y + 1 < size_.height) {
      const float* below = distance.ptr<float>(y + 1);
      const float* down = down_.ptr<float>(y);
      const float* down_left = down_left_.ptr<float>(y);
      const float* down_right = down_right_.ptr<float>(y);
      for (int x = 0; x < w; ++x) relax(d[x], below[x] + down[x], &changed);
      for (int x = 0; x + 1 < w; ++x) relax(d[x], below[x + 1] + down_right[x], &changed);
      for (int x = 1; x < w; ++x) relax(d[x], below[x - 1] + down_left[x], &changed);
    }
    for (int x = w - 2; x >= 0; --x) relax(d[x], d[x + 1] + right[x], &changed);
  }
  return changed;
}

}  // namespace movseg
