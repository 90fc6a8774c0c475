// Per-frame times in bounded memory: a run on a camera may last weeks, so its median comes from
// a histogram (0.05 ms bins up to 2 s, one overflow bin) instead of a list of every frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace movseg::cli {

class LatencyHistogram {
 public:
  void add(double ms) {
    const auto bin = static_cast<size_t>(std::clamp(ms, 0.0, kMaxMs) / kBinMs);
    ++bins_[std::min(bin, bins_.size() - 1)];
    ++count_;
  }
  // The median, to half a bin (0 when empty).
  double median() const {
    std::int64_t seen = 0;
    for (size_t i = 0; i < bins_.size(); ++i) {
      seen += bins_[i];
      if (2 * seen >= count_ && count_ > 0) return (static_cast<double>(i) + 0.5) * kBinMs;
    }
    return 0;
  }

 private:
  static constexpr double kBinMs = 0.05;
  static constexpr double kMaxMs = 2000.0;
  std::vector<std::int64_t> bins_ = std::vector<std::int64_t>(static_cast<size_t>(kMaxMs / kBinMs) + 1);
  std::int64_t count_ = 0;
};

}  // namespace movseg::cli
