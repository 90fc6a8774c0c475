// Wall-clock timing of the stages, for the *_ms fields of Diagnostics.
#pragma once

#include <chrono>

namespace movseg {

using Clock = std::chrono::steady_clock;

inline double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace movseg
