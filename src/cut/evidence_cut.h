// The mask that best agrees with per-pixel evidence and with the image's edges: a binary graph
// cut on 2x2 blocks of the evidence (a log-likelihood ratio, > 0 favouring foreground), with a
// contrast-sensitive smoothness term (GrabCut's), the blocks' labels then interpolated back.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

class GridMaxFlow;

// The cut's smoothness term: the weights of the edges between 2x2 blocks of a frame. It needs
// the frame alone, so a pipeline makes it in its first phase, beside the flow, and the second
// phase, which waits for the previous mask, only cuts.
struct BlockContrast {
  cv::Mat right, down;  // CV_32F at the blocks' size, as GridEnergy's
};

// `bgr` 8-bit BGR. `smoothness`: the weight of an edge between two blocks of equal colour, in
// units of evidence.
void blockContrast(const cv::Mat& bgr, double smoothness, BlockContrast* contrast);

// `evidence` CV_32F of the frame's size, `contrast` made from that frame. Returns CV_8U 0/255 of
// evidence's size; *nodes: the blocks left to the max-flow, solved in `memory` (grid_max_flow.h).
cv::Mat cutEvidence(const cv::Mat& evidence, const BlockContrast& contrast, GridMaxFlow* memory,
                    int* nodes);

}  // namespace movseg
