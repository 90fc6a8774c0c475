// The paper's sampling rule for RANSAC (§3.1): the points of one minimal sample are spread over
// the image instead of coming from one local area.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// RANSAC's Sampler (motion/ransac.h): buckets the points into a grid x grid partition of their
// image and draws each minimal sample from distinct, randomly chosen cells. Falls back to
// distinct uniform indices when too few cells are occupied. Deterministic for a given cv::RNG
// state.
class SpreadSampler {
 public:
  SpreadSampler(const std::vector<cv::Point2f>& points, cv::Size image_size, int grid);

  // Writes `count` distinct indices into `sample`; false when there are fewer points.
  bool sample(int count, cv::RNG& rng, std::vector<int>* sample) const;

 private:
  std::vector<std::vector<int>> cells_;  // occupied cells only
  int num_points_ = 0;
};

}  // namespace movseg
