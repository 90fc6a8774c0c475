// The scenario of the segmenter fuzz target, also replayed by tests/reliability/: Params within
// their valid ranges, then up to 8 frames of 1x1 to 96x96 pixels (any depth, 1 to 4 channels,
// size changes, flat, textured, shifted, noisy or raw-byte content) built from the input.
#pragma once

#include <cstddef>
#include <cstdint>

namespace movseg::fuzz {

// Feeds the frames to one Segmenter and checks each Result against Segmenter::process's
// contract. Throws std::logic_error naming the broken promise: a mask of the wrong type, size or
// values, a non-finite diagnostic, a supported frame rejected or an unsupported one accepted.
// Any other exception escaping process() propagates.
void runSegmenterInput(const std::uint8_t* data, std::size_t size);

}  // namespace movseg::fuzz
