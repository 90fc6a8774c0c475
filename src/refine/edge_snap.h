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

  // `mask` CV_8U 0/255, `grey` the frame's 8-bit brightness at the same size; `radius`
  // (pixels) is the filter's window radius, 0 returns `mask`. Returns the snapped mask, CV_8U
  // with 127 on the outline: the filter's output times 255, whose grey levels place the outline
  // between pixels when the mask is scaled up (upscaledMask). Elsewhere than on those thin
  // parts, the same as cv::ximgproc::guidedFilter of the mask with `grey` as guide, at a
  // fraction of its cost (tests/refine, bench BM_EdgeSnap).
  //
  // `output_grey`, when given, is the same frame's brightness at a larger size (the input's,
  // where the mask was made at a working scale): the result is then at that size, the filter's
  // slope and offset scaled up and applied to that image where the filter changed the mask
  // (He and Sun's "Fast guided filter", 2015), so that the outline follows its finer edges;
  // elsewhere, and on the thin parts, the result scaled up.
  //
  // The result is `mask` or the snap's own buffer, valid until the next call: at a fixed frame
  // size a snap allocates nothing.
  cv::Mat snap(const cv::Mat& mask, const cv::Mat& grey, int radius,
               const cv::Mat& output_grey = cv::Mat());

 private:
  // The working result `snapped` with the outline placed on `fine`'s edges (above).
  cv::Mat onFinerEdges(const cv::Mat& snapped, cv::Rect region, const cv::Mat& fine);

  // Kept between calls (frames of one size allocate them once), all over the region that holds
  // the outline: views into buffers of the mask's size (regionView).
  cv::Mat guide_, square_, label_, masked_guide_;
  cv::Mat mean_guide_, mean_square_, mean_label_, mean_masked_guide_;
  cv::Mat slope_, offset_, mean_slope_, mean_offset_, eroded_, opened_, state_;
  cv::Mat snapped_, finer_;  // the results, at the mask's size and at the finer edges'
  std::vector<float> scratch_;
  std::vector<uchar> line_, edge_;  // openWithCross's rows
  std::vector<int> first_;  // onFinerEdges' output columns by their left tap
  std::vector<bool> changed_rows_;
};

}  // namespace movseg
