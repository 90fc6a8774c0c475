// Boykov–Kolmogorov max-flow on the 4-connected pixel grid itself. The general solvers of
// max_flow.h need the graph built as lists of nodes and edges first, which on a grid where
// nearly every pixel is free costs as much as the flow; here a pixel's neighbours are found by
// their offset, and its four residual capacities sit beside its terminal one. Same algorithm
// (search trees from both terminals, augment, adopt orphans), same cut semantics as OpenCV's
// GCGraph: a pixel ends on the source (foreground) side unless the sink's tree holds it.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "cut/grid_energy.h"

namespace movseg {

// Keeps its nodes between calls, as OpenCV's DIS keeps its buffers: a pipeline that owns one
// allocates the graph of a frame size once, not per frame (a 320x240 grid is 2.8 MB, which
// glibc would otherwise hand back to the kernel and fault in again).
class GridMaxFlow {
 public:
  GridMaxFlow();
  ~GridMaxFlow();

  // The labelling (CV_8U 0/255, into *labels) that minimises `energy` over the kFree pixels of
  // `state`, the others keeping their fixed label (as labelFreePixels). *nodes: the free pixels.
  void label(const GridEnergy& energy, const cv::Mat& state, int* nodes, cv::Mat* labels);

  struct Node;  // a pixel's residual capacities and its place in the search trees

 private:
  std::vector<Node> nodes_;
  std::vector<int> orphans_;
};

}  // namespace movseg
