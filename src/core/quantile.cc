#include "core/quantile.h"

#include <algorithm>

namespace movseg {

float quantile(std::vector<float>* values, double q) {
  const auto k = values->begin() + static_cast<std::ptrdiff_t>(q * (values->size() - 1));
  std::nth_element(values->begin(), k, values->end());
  return *k;
}

int median(const LevelHistogram& histogram) {
  long count = 0;
  for (const long n : histogram) count += n;
  long seen = 0;
  for (int level = 0; level < 256; ++level) {
    seen += histogram[static_cast<size_t>(level)];
    if (seen > count / 2) return level;
  }
  return 255;
}

}  // namespace movseg
