#include "core/work_limit.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"

namespace movseg {
namespace {

// Each budget is about a hundred times what the defaults cost at a 320x240 working scale, and
// bounds a stage's time to a few seconds on one core (docs/reliability.md has the figures).
constexpr double kAlignmentPixels = 2e6;       // pixels of the alignment scale
constexpr double kFeatures = 30000;            // corners and edge points detected per frame
constexpr double kTrackingWork = 2e7;          // tracked x (LK window area x levels + ZNCC area)
constexpr double kRansacWork = 1e7;            // hypotheses x outer rounds x tracked features
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

// The width at which `frame` scaled from `width` (0 = native) has at most `pixels` pixels.
int widthWithin(cv::Size frame, int width, double pixels) {
  const cv::Size scaled = scaledSize(frame, width);
  if (area(scaled) <= pixels) return width;
  return std::max(1, static_cast<int>(scaled.width * std::sqrt(pixels / area(scaled))));
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

// A smaller segmentation scale, then less blur and a narrower band for the cut.
void limitSegmentation(cv::Size frame, Params* p) {
  p->segmentation_width = widthWithin(frame, p->segmentation_width, kSegmentationPixels);
  const cv::Size seg = scaledSize(frame, p->segmentation_width);
  p->difference_blur = std::min(p->difference_blur, kBlurWork / area(seg));
  if (cutNodes(seg, p->cut_band) > kCutNodes) {
    p->cut_band = std::max(1, static_cast<int>(kCutNodes / (32.0 * (seg.width + seg.height))));
  }
}

bool sameWork(const Params& a, const Params& b) {
  return a.alignment_width == b.alignment_width && a.max_corners == b.max_corners &&
         a.edge_cell == b.edge_cell &&
         a.max_tracked_features == b.max_tracked_features &&
         a.ransac_iterations == b.ransac_iterations &&
         a.segmentation_width == b.segmentation_width && a.difference_blur == b.difference_blur &&
         a.cut_band == b.cut_band;
}

}  // namespace

WorkLimit withinWorkLimit(const Params& params, cv::Size frame) {
  WorkLimit limit{params, false};
  limit.params.alignment_width = widthWithin(frame, params.alignment_width, kAlignmentPixels);
  limitFeatures(scaledSize(frame, limit.params.alignment_width), &limit.params);
  limitTracking(&limit.params);
  limitSegmentation(frame, &limit.params);
  limit.lowered = !sameWork(limit.params, params);
  return limit;
}

}  // namespace movseg
