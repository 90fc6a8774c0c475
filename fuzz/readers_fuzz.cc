// libFuzzer entry point: the ground-truth, mask and frame readers on the files of
// readers_input.h.
#include <cstddef>
#include <cstdint>

#include "readers_input.h"
#include "scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const movseg::fuzz::Scratch scratch;
  movseg::fuzz::runReadersInput(data, size, scratch.path() + "/input");
  return 0;
}
