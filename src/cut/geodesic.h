// §3.3 geodesic distances to the seeds (eq. 9, 10), by raster scanning (ref. [19]).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// The 8-connected pixel grid of an image with the geodesic step cost
//   c(p, q) = sqrt(|p - q|^2 + gamma^2 |C(p) - C(q)|^2),   colours C in [0, 1]^3,
// precomputed once per image and shared by the foreground and background distances.
class GeodesicGrid {
 public:
  // `colour`: CV_32FC3 in [0, 1].
  GeodesicGrid(const cv::Mat& colour, double gamma);

  // Shortest-path distance from every pixel to the nearest seed (CV_32F), by pairs of forward
  // and backward raster passes until nothing changes, at most `max_sweeps` pairs. Each pair
  // follows paths that turn back at most once per direction, so a few pairs are exact on most
  // images and one is close (docs/design.md). Without seeds every distance is +infinity.
  cv::Mat distanceFrom(const std::vector<cv::Point>& seeds, int max_sweeps) const;

 private:
  // Each returns whether any distance decreased.
  bool forwardPass(cv::Mat& distance) const;
  bool backwardPass(cv::Mat& distance) const;

  cv::Size size_;
  // Cost of the step from (x, y) to its neighbour right, down-left, down, down-right.
  cv::Mat right_, down_left_, down_, down_right_;
};

}  // namespace movseg
