// The mask's outline moved onto the image's edges. `dense` cuts 2x2 blocks, so its outline can
// run a block off the mover's; a guided filter of the mask with the frame's brightness as its
// guide (He, Sun and Tang, "Guided image filtering", 2013) makes the mask, within each window,
// a linear function of the brightness, so that its half level follows the edge nearest the
// cut's outline. Only the outline moves: a window that the mask fills or leaves empty keeps its
// label exactly, and so do the mask's parts too thin for any window.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

class EdgeSnap {
 public:
  // The filter's regulariser, in squared grey levels: within a window whose brightness varies
  // less than about 10 levels, the mask is smoothed rather than made to follow the image, so
  // that noise and faint texture do not shape the outline (300: DAVIS J 0.0003 less;
  // docs/design.md, "Edges").
  static constexpr float kRegulariser = 100.f;

  // `mask` CV_8U 0/255, `bgr` 8-bit BGR of the same size; `radius` (pixels) is the filter's
  // window radius, 0 returns `mask`. Returns the snapped mask, CV_8U with 127 on the outline:
  // the filter's output times 255, whose grey levels place the outline between pixels when the
  // mask is scaled up (upscaledMask). Elsewhere than on those thin parts, the same as
  // cv::ximgproc::guidedFilter of the mask with the grey frame as guide, at a fraction of its
  // cost (tests/refine, bench BM_EdgeSnap).
  cv::Mat snap(const cv::Mat& mask, const cv::Mat& bgr, int radius);

 private:
  // Kept between calls (frames of one size allocate them once), all over the region that holds
  // the outline.
  cv::Mat grey_, guide_, square_, label_, masked_guide_;
  cv::Mat mean_guide_, mean_square_, mean_label_, mean_masked_guide_;
  cv::Mat slope_, offset_, mean_slope_, mean_offset_, opened_;
  std::vector<float> scratch_;
};

}  // namespace movseg
