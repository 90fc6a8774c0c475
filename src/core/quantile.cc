#include "core/quantile.h"

#include <algorithm>

namespace movseg {

float quantile(std::vector<float>* values, double q) {
  const auto k = values->begin() + static_cast<std::ptrdiff_t>(q * (values->size() - 1));
  std::nth_element(values->begin(), k, values->end());
  return *k;
}

}  // namespace movseg
