// The per-frame work limit: no valid Params may make one frame take minutes. Each stage's work
// grows with a product of parameters (features x window area x levels for Lucas-Kanade,
// hypotheses x rounds x matches for RANSAC, ...); where a product exceeds its budget for the
// frame's pixels, the parameter that drives it is lowered. Only the stages of Params::method
// count. The defaults stay far below every budget, at any frame size (docs/reliability.md has
// the figures).
#pragma once

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

struct WorkLimit {
  Params params;         // the parameters a stream of this frame size runs with
  bool lowered = false;  // some were lowered (Diagnostics::work_limited)
};

WorkLimit withinWorkLimit(const Params& params, cv::Size frame);

}  // namespace movseg
