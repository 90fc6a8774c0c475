// The mask that best agrees with per-pixel evidence and with the image's edges: a binary graph
// cut on 2x2 blocks of the evidence (a log-likelihood ratio, > 0 favouring foreground), with a
// contrast-sensitive smoothness term (GrabCut's), the blocks' labels then interpolated back.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

class GridMaxFlow;

// `evidence` CV_32F and `bgr` 8-bit BGR of the same size. `smoothness`: the weight of an edge
// between two blocks of equal colour, in units of evidence. Returns CV_8U 0/255 of bgr's size;
// *nodes: the blocks left to the max-flow, solved in `memory` (grid_max_flow.h).
cv::Mat cutEvidence(const cv::Mat& evidence, const cv::Mat& bgr, double smoothness,
                    GridMaxFlow* memory, int* nodes);

}  // namespace movseg
