// libFuzzer entry point: video containers through the FFmpeg reader into a Segmenter
// (video_input.h).
#include <cstddef>
#include <cstdint>

#include "scratch.h"
#include "video_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const movseg::fuzz::Scratch scratch;
  movseg::fuzz::runVideoInput(data, size, scratch.path() + "/input.video");
  return 0;
}
