// The largest image a frame file may decode to: OpenCV's own limits (CV_IO_MAX_IMAGE_WIDTH,
// _HEIGHT and _PIXELS, unless its environment raises them), which cv::imread checks against the
// header before it allocates anything. movseg's own decoders check the same, so that a few
// hundred bytes claiming 33000x33000 pixels are refused at once rather than decoded into 3 GB.
#pragma once

#include <cstdint>

namespace movseg {

inline bool withinImageLimits(std::uint64_t width, std::uint64_t height) {
  constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20, kMaxPixels = std::uint64_t{1} << 30;
  return width <= kMaxSide && height <= kMaxSide && width * height <= kMaxPixels;
}

}  // namespace movseg
