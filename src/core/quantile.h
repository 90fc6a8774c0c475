// Order statistics of sample values, for scales measured on the frame's own data.
#pragma once

#include <vector>

namespace movseg {

// The value at fraction q in [0, 1] of `values` in increasing order: the element of index
// q * (n - 1), rounded down, without interpolation. Reorders *values; n must be positive.
float quantile(std::vector<float>* values, double q);

}  // namespace movseg
