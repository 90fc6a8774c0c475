#include "motion/spread_sampler.h"

#include <algorithm>

namespace movseg {

SpreadSampler::SpreadSampler(const std::vector<cv::Point2f>& points, cv::Size image_size,
                             int grid) {
  reset(points, image_size, grid);
}

void SpreadSampler::reset(const std::vector<cv::Point2f>& points, cv::Size image_size, int grid) {
  num_points_ = static_cast<int>(points.size());
  const float cell_w = static_cast<float>(image_size.width) / grid;
  const float cell_h = static_cast<float>(image_size.height) / grid;
  const auto grid_cells = static_cast<size_t>(grid) * grid;
  // next_[c + 1] counts cell c's points, then (summed) next_[c] is where cell c starts.
  next_.assign(grid_cells + 1, 0);
  cell_of_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const int cx = std::clamp(static_cast<int>(points[i].x / cell_w), 0, grid - 1);
    const int cy = std::clamp(static_cast<int>(points[i].y / cell_h), 0, grid - 1);
    cell_of_[i] = cy * grid + cx;
    ++next_[static_cast<size_t>(cell_of_[i]) + 1];
  }
  cells_.clear();
  for (size_t c = 0; c < grid_cells; ++c) {
    if (next_[c + 1] > 0) cells_.push_back({next_[c], next_[c] + next_[c + 1]});
    next_[c + 1] += next_[c];
  }
  members_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    members_[static_cast<size_t>(next_[static_cast<size_t>(cell_of_[i])]++)] = static_cast<int>(i);
  }
}

bool SpreadSampler::sample(int count, cv::RNG& rng, std::vector<int>* sample) const {
  sample->clear();
  if (num_points_ < count) return false;
  const int num_cells = static_cast<int>(cells_.size());
  if (num_cells >= count) {
    chosen_.clear();
    while (static_cast<int>(chosen_.size()) < count) {
      const int c = rng.uniform(0, num_cells);
      if (std::find(chosen_.begin(), chosen_.end(), c) != chosen_.end()) continue;
      chosen_.push_back(c);
      const Cell& cell = cells_[static_cast<size_t>(c)];
      const int member = cell.begin + rng.uniform(0, cell.end - cell.begin);
      sample->push_back(members_[static_cast<size_t>(member)]);
    }
    return true;
  }
  while (static_cast<int>(sample->size()) < count) {
    const int i = rng.uniform(0, num_points_);
    if (std::find(sample->begin(), sample->end(), i) == sample->end()) sample->push_back(i);
  }
  return true;
}

}  // namespace movseg
