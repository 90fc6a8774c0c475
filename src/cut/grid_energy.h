// A binary labelling energy on the 4-connected pixel grid, the form of eq. (6): a cost for each
// label of each pixel, and a weight on each edge paid when its two pixels disagree. Solved
// exactly by max-flow on the pixels that need it, whole or coarse to fine.
#pragma once

#include <opencv2/core.hpp>

#include "cut/max_flow.h"

namespace movseg {

class GridMaxFlow;

struct GridEnergy {
  cv::Mat cost_fg, cost_bg;  // CV_32F: the cost of labelling each pixel foreground / background
  cv::Mat right, down;       // CV_32F: the weight of the edge to the right / lower neighbour
                             // (0 in the last column / row)
};

// Fills energy->right and energy->down (in their buffers when of the size) with |C_i - C_j|^2
// between each pixel of `colour` (CV_32FC3) and its right and lower neighbour (0 where there is
// none), and returns GrabCut's beta = 1 / (2 <|dC|^2>) over those edges (0 for a flat image):
// scaled by beta, a contrast term reacts to the image's own contrast whatever its bit depth or
// dynamic range. The callers turn the squared steps into their edge weights.
float squaredColourSteps(const cv::Mat& colour, GridEnergy* energy);

// Where a pixel's label comes from in a solve.
enum PixelState : uchar { kFree = 0, kFixedBackground = 1, kFixedForeground = 2 };

// Exact reduction: a pixel whose unary preference |cost_bg - cost_fg| exceeds the sum of its
// edge weights takes its preferred label in every minimum (flipping it would cost more than any
// agreement it could buy), so it needs no node in the max-flow graph. *state: CV_8U of
// PixelState.
void decidedPixels(const GridEnergy& energy, cv::Mat* state);

// The labelling (CV_8U 0/255) that minimises the energy over the kFree pixels of `state`, the
// others keeping their fixed label; a free pixel's edge to a fixed one becomes part of its
// unary cost. *nodes: the free pixels. `memory`: where kGrid's solver keeps its nodes between
// calls (a pipeline's own, so that its frames reuse them); null: a temporary one.
cv::Mat labelFreePixels(const GridEnergy& energy, const cv::Mat& state, MaxFlowSolver solver,
                        int* nodes, GridMaxFlow* memory = nullptr);

// The energy of 2x2 blocks: a block's costs are the sums of its pixels', the weight between two
// blocks the sum of the pixel edges that cross from one to the other. So a labelling of the
// blocks costs what the same labelling of their pixels costs.
GridEnergy coarsened(const GridEnergy& energy);

// Minimises the energy over the free pixels of `state` in two steps: the 2x2 blocks first
// (each block free when any of its pixels is), then the pixels within `refine` of a boundary of
// the blocks' labelling, the others keeping their block's label. Not exact: a boundary is found
// at the coarse scale and moved by at most `refine` pixels. *nodes: both graphs' nodes;
// `memory` as labelFreePixels'.
cv::Mat labelCoarseToFine(const GridEnergy& energy, const cv::Mat& state, int refine,
                          MaxFlowSolver solver, int* nodes, GridMaxFlow* memory = nullptr);

// Fixes every free pixel of `state` farther than `band` (Chebyshev distance) from the boundary
// of `labels` (CV_8U 0/255) to its label there.
void fixAwayFromBoundary(const cv::Mat& labels, int band, cv::Mat* state);

}  // namespace movseg
