#include "motion/ransac.h"

#include <stdexcept>
#include <string>

namespace movseg {

void RansacOptions::check() const {
  // The message is made only for an option out of range: a check allocates nothing.
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("invalid RANSAC option: ") + what);
  };
  require(max_trials >= 1, "max_trials must be at least 1");
  require(std::isfinite(max_error) && max_error > 0, "max_error must be positive");
  require(confidence > 0 && confidence < 1, "confidence must be in (0, 1)");
  require(sample_grid >= 1, "sample_grid must be at least 1");
}

}  // namespace movseg
