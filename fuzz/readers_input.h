// The scenario of the readers fuzz target, also replayed by tests/reliability/: files with
// fuzzed names and contents laid out as a ground-truth sequence (plain, DAVIS, SegTrack or CDnet
// with its temporalROI.txt, alone or in a dataset folder) beside a folder of predictions, then
// read the way `movseg segment` and `movseg eval` read them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace movseg::fuzz {

// Empties `scratch` (a folder of its own), writes the files there and reads them: the ground
// truth and its masks, the scores against the predictions, and the frames through FrameSource
// into a Segmenter. A bad file may only end in std::runtime_error (or std::invalid_argument
// from process() for a decoded image of unsupported type). Throws std::logic_error naming the
// broken promise when a mask read is not 0/255 or a score is not finite; any other exception
// propagates.
void runReadersInput(const std::uint8_t* data, std::size_t size, const std::string& scratch);

}  // namespace movseg::fuzz
