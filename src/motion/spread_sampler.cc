#include "motion/spread_sampler.h"

#include <algorithm>

namespace movseg {

SpreadSampler::SpreadSampler(const std::vector<cv::Point2f>& points, cv::Size image_size, int grid)
    : num_points_(static_cast<int>(points.size())) {
  std::vector<std::vector<int>> cells(static_cast<size_t>(grid) * grid);
  const float cell_w = static_cast<float>(image_size.width) / grid;
  const float cell_h = static_cast<float>(image_size.height) / grid;
  for (int i = 0; i < num_points_; ++i) {
    const int cx = std::clamp(static_cast<int>(points[i].x / cell_w), 0, grid - 1);
    const int cy = std::clamp(static_cast<int>(points[i].y / cell_h), 0, grid - 1);
    cells[static_cast<size_t>(cy) * grid + cx].push_back(i);
  }
  for (auto& cell : cells) {
    if (!cell.empty()) cells_.push_back(std::move(cell));
  }
}

bool SpreadSampler::sample(int count, cv::RNG& rng, std::vector<int>* sample) const {
  sample->clear();
  if (num_points_ < count) return false;
  const int num_cells = static_cast<int>(cells_.size());
  if (num_cells >= count) {
    std::vector<int> chosen;
    while (static_cast<int>(chosen.size()) < count) {
      const int c = rng.uniform(0, num_cells);
      if (std::find(chosen.begin(), chosen.end(), c) != chosen.end()) continue;
      chosen.push_back(c);
      const auto& cell = cells_[static_cast<size_t>(c)];
      sample->push_back(cell[static_cast<size_t>(rng.uniform(0, static_cast<int>(cell.size())))]);
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
