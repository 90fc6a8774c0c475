// Order statistics of sample values, for scales measured on the frame's own data.
#pragma once

#include <array>
#include <vector>

namespace movseg {

// The value at fraction q in [0, 1] of `values` in increasing order: the element of index
// q * (n - 1), rounded down, without interpolation. Reorders *values; n must be positive.
float quantile(std::vector<float>* values, double q);

// How many 8-bit values of each level were seen.
using LevelHistogram = std::array<long, 256>;

// The median of the values a histogram counts: the lowest level with more than half of them at
// or below it; 255 when it counts none.
int median(const LevelHistogram& histogram);

}  // namespace movseg
