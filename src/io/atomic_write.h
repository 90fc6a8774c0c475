// Output files appear whole or not at all: written to a temporary name beside the target, then
// renamed over it (rename is atomic on POSIX), so an interrupted run never leaves half a file.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace movseg {

// Encodes `image` by the path's extension (.png, .jpg, ...). Throws std::runtime_error naming
// the path when it cannot be encoded or written.
void writeImageAtomic(const std::string& path, const cv::Mat& image);

void writeTextAtomic(const std::string& path, const std::string& text);

}  // namespace movseg
