// Accuracy of a method on a synthetic clip, for the end-to-end tests of each pipeline.
#pragma once

#include <functional>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "synth/synth.h"

namespace movseg::test {

// What a test does to frame t of a clip before the segmenter sees it.
using FrameChange = std::function<void(int t, cv::Mat* frame)>;

// The frame in grey (a thermal or night camera).
void toGrey(int t, cv::Mat* frame);

// Mean IoU of `params`' masks against the clip's truth, over the frames after the first
// (a frame with nothing to find and nothing found counts 1), each frame changed by `change`
// when one is given. With an `ignored` region (Segmenter::setIgnoredRegion, of the frames'
// size), the truth counts outside it only.
double meanIou(const SynthOptions& clip, const Params& params, const FrameChange& change = {},
               const cv::Mat& ignored = cv::Mat());

}  // namespace movseg::test
