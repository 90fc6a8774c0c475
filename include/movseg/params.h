// movseg — moving object segmentation for freely moving cameras: the parameters.
// The fields, their defaults, ranges and documentation are in movseg/params.def.
#pragma once

#include <cstdint>

namespace movseg {

// Which pipeline turns frames into masks (Params::method).
enum class Method {
  kPaper,            // "paper": the publication's pipeline (§3.1–§3.3)
  kDiff,             // "diff": the compensated difference thresholded by eq. (3)
  kMog2,             // "mog2": OpenCV's MOG2, no camera compensation
  kMog2Compensated,  // "mog2-comp": MOG2 in a frame stabilised by §3.1's camera model
  kDense,            // "dense": dense residual motion with memory and colour (movseg's own)
};

// The frame-to-frame camera model of §3.1.
enum class MotionModel {
  kAffine,      // "affine": eq. (1), the paper's
  kHomography,  // "homography"
};

struct Params {
#define MOVSEG_PARAM(type, name, default_value, min, max, step, unit, doc) \
  type name = default_value;
#include "movseg/params.def"
#undef MOVSEG_PARAM

  // Throws std::invalid_argument naming the first parameter out of its range.
  void check() const;
};

// Every field equal.
bool operator==(const Params& a, const Params& b);
inline bool operator!=(const Params& a, const Params& b) { return !(a == b); }

}  // namespace movseg
