// The scenario of the video fuzz target, also replayed by tests/reliability/: the input is a
// video file (the corpus starts from small mp4, mkv, mov and avi files made by FFmpeg, damaged,
// truncated, joined at different sizes), read the way `movseg segment` reads one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace movseg::fuzz {

// Writes the bytes to `path` and reads up to 8 frames of it through FrameSource into a
// Segmenter. Opening and reading may only fail with std::runtime_error; every frame must be
// 8-bit BGR and give a mask of its size, and every decode error counted must have its text.
// Throws std::logic_error naming a broken promise; any other exception propagates.
void runVideoInput(const std::uint8_t* data, std::size_t size, const std::string& path);

}  // namespace movseg::fuzz
