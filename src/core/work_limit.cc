#include "core/work_limit.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"

namespace movseg {
namespace {

// Each budget is about a hundred times what the defaults cost at a 320x240 working scale, and
// bounds a stage's time to a few seconds on one core (docs/reliability.md has the figures).
constexpr double kAlignmentPixels = 2e6;       // pixels of the alignment scale
constexpr double kFeatures = 30000;            // corners and edge points, or flow samples
constexpr double kTrackingWork = 2e7;          // tracked x (LK window area x levels + ZNCC area)
constexpr double kRansacWork = 1e7;            // hypotheses x outer rounds x tracked features,
                                               // or hypotheses x flow samples
constexpr double kSegmentationPixels = 1e6;    // pixels of the segmentation scale
constexpr double kBlurWork = 2e7;              // segmentation pixels x blur sigma
constexpr double kCutNodes = 400000;           // max-flow nodes, estimated from the band

double area(cv::Size size) { return static_cast<double>(size.width) * size.height; }

// Max-flow nodes of a band of `band` pixels each side of the geodesic boundary, taking the
// boundary as 16 times the frame's half perimeter (a textured 4K pair with the densest seeds
// measured 14); the whole image for 0.
double cutNodes(cv::Size size, int band) {
  const double whole = area(size);
  return band == 0 ? whole : std::min(whole, 32.0 * band * (size.width + size.height));
}

// The working width (workingSize) at which `frame` scaled from `width` (0 = native) has at most
// `pixels` pixels.
int widthWithin(cv::Size frame, int width, double pixels) {
  const cv::Size scaled = workingSize(frame, width);
  if (area(scaled) <= pixels) return width;
  const int longer = std::max(scaled.width, scaled.height);
  return std::max(1, static_cast<int>(longer * std::sqrt(pixels / area(scaled))));
}

// Fewer features: at most half the budget for corners, the rest for edge points (one per
// edge_cell x edge_cell cell of the alignment scale).
void limitFeatures(cv::Size align, Params* p) {
  p->max_corners = std::min(p->max_corners, static_cast<int>(kFeatures / 2));
  const double cells = kFeatures - p->max_corners;
  const int cell = static_cast<int>(std::ceil(std::sqrt(area(align) / cells)));
  p->edge_cell = std::clamp(cell, p->edge_cell, 1024);
}

void limitTracking(Params* p) {
  const double per_track = static_cast<double>(p->lk_window) * p->lk_window * (p->lk_levels + 1) +
                           static_cast<double>(p->zncc_window) * p->zncc_window;
  const int tracked = static_cast<int>(kTrackingWork / per_track);
  p->max_tracked_features = std::min(p->max_tracked_features, std::max(32, tracked));
  const int hypotheses =
      static_cast<int>(kRansacWork / (static_cast<double>(p->max_outer_iterations) * p->max_tracked_features));
  p->ransac_iterations = std::min(p->ransac_iterations, std::max(1, hypotheses));
}

// The camera tracker's stages (paper, diff, mog2-comp): alignment scale, features, tracking and
// the two-layer RANSAC.
void limitTracker(cv::Size frame, Params* p) {
  p->alignment_width = widthWithin(frame, p->alignment_width, kAlignmentPixels);
  limitFeatures(workingSize(frame, p->alignment_width), p);
  limitTracking(p);
}

// Less blur at the segmentation scale `seg` (the tracker prepares eq. (4)'s blurred images).
void limitBlur(cv::Size seg, Params* p) {
  p->difference_blur = std::min(p->difference_blur, kBlurWork / area(seg));
}

// A narrower band for the paper's cut.
void limitCut(cv::Size seg, Params* p) {
  if (cutNodes(seg, p->cut_band) > kCutNodes) {
    p->cut_band = std::max(1, static_cast<int>(kCutNodes / (32.0 * (seg.width + seg.height))));
  }
}

// Dense: the camera is fitted to one flow sample every flow_sample_step pixels, by
// ransac_iterations hypotheses.
void limitFlowCamera(cv::Size seg, Params* p) {
  const int step = static_cast<int>(std::ceil(std::sqrt(area(seg) / kFeatures)));
  p->flow_sample_step = std::clamp(step, p->flow_sample_step, 64);
  const double samples = area(seg) / (static_cast<double>(p->flow_sample_step) * p->flow_sample_step);
  p->ransac_iterations =
      std::min(p->ransac_iterations, std::max(1, static_cast<int>(kRansacWork / samples)));
}

}  // namespace

WorkLimit withinWorkLimit(const Params& params, cv::Size frame) {
  WorkLimit limit{params, false};
  Params& p = limit.params;
  // Every method works at the segmentation scale; the rest is the method's own.
  p.segmentation_width = widthWithin(frame, p.segmentation_width, kSegmentationPixels);
  const cv::Size seg = workingSize(frame, p.segmentation_width);
  switch (p.method) {
    case Method::kPaper:
      limitTracker(frame, &p);
      limitBlur(seg, &p);
      limitCut(seg, &p);
      break;
    case Method::kDiff:
    case Method::kMog2Compensated:
      limitTracker(frame, &p);
      limitBlur(seg, &p);
      break;
    case Method::kMog2: break;
    case Method::kDense: limitFlowCamera(seg, &p); break;
  }
  limit.lowered = limit.params != params;
  return limit;
}

}  // namespace movseg
