// How RANSAC ranks its hypotheses (the SupportMeasurer of motion/ransac.h).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// First how much of the image the inliers cover (occupied cells of a kGrid x kGrid grid), then
// how many there are. The background spans the image while a moving object is local, so
// coverage keeps a densely textured object from winning on numbers alone (docs/design.md).
class CoverageSupportMeasurer {
 public:
  static constexpr int kGrid = 8;

  struct Support {
    int cells = 0;
    int num_inliers = 0;
  };

  CoverageSupportMeasurer() = default;
  // `points`: where the correspondences lie, in an image of `image_size`.
  CoverageSupportMeasurer(const std::vector<cv::Point2f>& points, cv::Size image_size);

  // The same for a new set of points, in the storage of the last.
  void reset(const std::vector<cv::Point2f>& points, cv::Size image_size);

  // Storage for as many points, so that no reset up to that many allocates.
  void reserve(size_t points) { cell_.reserve(points); }

  // The support of a hypothesis whose squared residuals are `residuals`.
  Support evaluate(const std::vector<double>& residuals, double max_residual) const;

  // Whether `a` is strictly better than `b`.
  static bool better(const Support& a, const Support& b) {
    return a.cells != b.cells ? a.cells > b.cells : a.num_inliers > b.num_inliers;
  }

 private:
  std::vector<int> cell_;  // per point
};

}  // namespace movseg
