// The simple methods a practitioner tries first, to measure the paper's pipeline against.
#pragma once

#include <memory>

#include "methods/method.h"

namespace movseg {

// `diff`: the compensated frame difference of §3.1 thresholded by eq. (3), i.e. the pipeline
// cut off before §3.2 (no GMM refinement, no geodesic cut).
std::unique_ptr<Method> makeDiffMethod(const Params& params);

// `mog2`: OpenCV's MOG2 background subtractor on the raw frames (no camera compensation).
std::unique_ptr<Method> makeMog2Method(const Params& params);

// `mog2-comp`: MOG2 whose background model stays aligned with the scene: frames are warped
// into a reference frame by the accumulated camera model of §3.1, MOG2 runs there, and its
// mask is warped back.
std::unique_ptr<Method> makeCompensatedMog2Method(const Params& params);

}  // namespace movseg
