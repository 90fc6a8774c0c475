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
  SpreadSampler() = default;
  SpreadSampler(const std::vector<cv::Point2f>& points, cv::Size image_size, int grid);

  // Buckets a new set of points, in the storage of the last: a RANSAC that owns its sampler
  // allocates nothing once it has seen as many points and cells.
  void reset(const std::vector<cv::Point2f>& points, cv::Size image_size, int grid);

  // Storage for as many points, so that no reset up to that many allocates.
  void reserve(size_t points) {
    members_.reserve(points);
    cell_of_.reserve(points);
  }

  // Writes `count` distinct indices into `sample`; false when there are fewer points.
  bool sample(int count, cv::RNG& rng, std::vector<int>* sample) const;

 private:
  // The occupied cells in the grid's raster order, each a range of members_, which holds every
  // point's index grouped by cell (a counting sort), in increasing order within a cell.
  struct Cell {
    int begin, end;
  };
  std::vector<Cell> cells_;
  std::vector<int> members_;
  std::vector<int> cell_of_;  // per point; scratch of reset()
  std::vector<int> next_;     // per grid cell, where its next member goes; scratch of reset()
  mutable std::vector<int> chosen_;  // the cells of a sample; scratch of sample()
  int num_points_ = 0;
};

}  // namespace movseg
