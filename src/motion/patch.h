// Sub-pixel patches of an 8-bit grey image, sampled straight into a caller's buffer: the
// per-feature ZNCC (eq. 2) and point differences (eq. 4) run on hundreds of tiny patches per
// frame, where cv::getRectSubPix's per-call Mat allocations cost more than the arithmetic.
#pragma once

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace movseg {

// Writes the side x side patch centred on `centre` (bilinear, border pixels replicated) into
// out[0 .. side*side).
inline void samplePatch(const cv::Mat& grey, cv::Point2f centre, int side, float* out) {
  CV_DbgAssert(grey.type() == CV_8UC1);
  const float half = static_cast<float>(side - 1) / 2.f;
  const float x0 = centre.x - half, y0 = centre.y - half;
  const float fx = std::floor(x0), fy = std::floor(y0);
  const float ax = x0 - fx, ay = y0 - fy;
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const int max_x = grey.cols - 1, max_y = grey.rows - 1;
  if (ix >= 0 && iy >= 0 && ix + side <= max_x && iy + side <= max_y) {
    // Inside: no pixel to replicate, the same arithmetic without clamps, which GCC vectorises.
    for (int r = 0; r < side; ++r) {
      const uchar* row0 = grey.ptr<uchar>(iy + r) + ix;
      const uchar* row1 = row0 + grey.step[0];
      float* row_out = out + r * side;
      for (int c = 0; c < side; ++c) {
        const float top = row0[c] + ax * (row0[c + 1] - row0[c]);
        const float bottom = row1[c] + ax * (row1[c + 1] - row1[c]);
        row_out[c] = top + ay * (bottom - top);
      }
    }
    return;
  }
  for (int r = 0; r < side; ++r) {
    const uchar* row0 = grey.ptr<uchar>(std::clamp(iy + r, 0, max_y));
    const uchar* row1 = grey.ptr<uchar>(std::clamp(iy + r + 1, 0, max_y));
    for (int c = 0; c < side; ++c) {
      const int xa = std::clamp(ix + c, 0, max_x), xb = std::clamp(ix + c + 1, 0, max_x);
      const float top = row0[xa] + ax * (row0[xb] - row0[xa]);
      const float bottom = row1[xa] + ax * (row1[xb] - row1[xa]);
      out[r * side + c] = top + ay * (bottom - top);
    }
  }
}

}  // namespace movseg
