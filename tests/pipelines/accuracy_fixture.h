// Accuracy of a method on a synthetic clip, for the end-to-end tests of each pipeline.
#pragma once

#include "movseg/params.h"
#include "synth/synth.h"

namespace movseg::test {

// Mean IoU of `params`' masks against the clip's truth, over the frames after the first
// (a frame with nothing to find and nothing found counts 1). With `grey`, the frames are given
// to the segmenter in grey.
double meanIou(const SynthOptions& clip, const Params& params, bool grey = false);

}  // namespace movseg::test
