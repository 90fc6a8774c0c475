// libFuzzer entry point: Segmenter::process on the frame sequences of segmenter_input.h.
#include <cstddef>
#include <cstdint>

#include "segmenter_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  movseg::fuzz::runSegmenterInput(data, size);
  return 0;
}
