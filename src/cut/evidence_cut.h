// The mask that best agrees with per-pixel evidence and with the image's edges: a binary graph
// cut on 2x2 blocks of the evidence (a log-likelihood ratio, > 0 favouring foreground), with a
// contrast-sensitive smoothness term (GrabCut's), the blocks' labels then interpolated back.
#pragma once

#include <opencv2/core.hpp>

#include "cut/grid_max_flow.h"

namespace movseg {

// The cut's smoothness term: the weights of the edges between 2x2 blocks of a frame. It needs
// the frame alone, so a pipeline makes it in its first phase, beside the flow, and the second
// phase, which waits for the previous mask, only cuts.
struct BlockContrast {
  cv::Mat right, down;  // CV_32F at the blocks' size, as GridEnergy's
  cv::Mat block_bgr, colour;  // scratch of blockContrast()
};

// `bgr` 8-bit BGR. `smoothness`: the weight of an edge between two blocks of equal colour, in
// units of evidence. Written in `contrast`'s buffers when they are of the size.
void blockContrast(const cv::Mat& bgr, double smoothness, BlockContrast* contrast);

// The cuts of a stream's frames, in buffers kept from one frame to the next, the max-flow's
// nodes (grid_max_flow.h) among them: at a fixed frame size a cut allocates nothing.
class EvidenceCut {
 public:
  // `evidence` CV_32F of the frame's size, `contrast` made from that frame. Writes *mask, CV_8U
  // 0/255 of evidence's size; *nodes: the blocks left to the max-flow.
  void cut(const cv::Mat& evidence, const BlockContrast& contrast, int* nodes, cv::Mat* mask);

 private:
  GridMaxFlow max_flow_;
  cv::Mat block_evidence_, cost_fg_, cost_bg_, decided_, labels_;
};

}  // namespace movseg
