// §3.3 foreground extraction: the energy of eq. (6)-(11) minimised by max-flow.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "cut/max_flow.h"
#include "movseg/params.h"

namespace movseg {

struct CutResult {
  cv::Mat mask;        // CV_8U 0/255
  cv::Mat confidence;  // u(x) of eq. (10), CV_32F (for the debug picture)
  int graph_nodes = 0; // max-flow nodes left after the exact reduction (with cut_refine: the
                       // 2x2 blocks', then the band's pixels')
};

class GridMaxFlow;

// Segments `bgr` from foreground and background seed pixels. Needs at least one seed of each.
// `memory`: where the kGrid solver keeps its nodes between calls (labelFreePixels).
CutResult geodesicGraphCut(const cv::Mat& bgr, const std::vector<cv::Point>& foreground,
                           const std::vector<cv::Point>& background, const Params& params,
                           MaxFlowSolver solver = MaxFlowSolver::kGrid,
                           GridMaxFlow* memory = nullptr);

}  // namespace movseg
