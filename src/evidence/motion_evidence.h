// Per-pixel evidence of independent motion, as a log-likelihood ratio of "moves" to "static",
// from the residual motion the camera model leaves, scaled by what that residual is on the
// pair's own background (each video, each pair, has its own flow noise, blur and parallax).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "evidence/bilinear_remap.h"
#include "evidence/box_mean.h"
#include "movseg/params.h"

namespace movseg {

// The residual that counts as "as large as the background's": the upper `evidence_quantile` of
// the residual at the samples, at least `evidence_median_factor` times their median (a pair
// whose samples hardly move must not read every flicker as motion) and a tenth of a pixel.
// Reorders *sample_residuals.
float residualScale(std::vector<float>* sample_residuals, const Params& params);

// evidence = clip(gain * (residual / scale - offset), min, max), CV_32F.
void motionEvidence(const cv::Mat& residual, float scale, const Params& params, cv::Mat* evidence);

// A change of light between two frames (exposure, flicker, a lamp switched on): the current
// frame's grey levels as an affine map of the previous frame's, gain * previous + offset.
struct LevelMap {
  double gain = 1, offset = 0;
  bool identity() const { return gain == 1 && offset == 0; }
  // The map as a table of the 256 levels, rounded and saturated.
  void table(uchar levels[256]) const;
};

// Flow bleeds: where a patch is flat, DIS gives it the motion of its textured neighbour, and
// a residual alone cannot tell. The previous frame brought to the current one by the camera and
// by the flow answers it: where the camera explains the pixels as well as the flow does, there
// is no evidence of motion, however large the residual. Both explanations are scored by their
// mean absolute difference over a patch; the confirmation is how much the flow's is smaller, in
// units of `photometric_margin` times the frame's median difference under the camera (its
// noise, blur and gain change), clipped to [-1, 1]: negative where the camera explains the patch
// better than the flow, i.e. where the flow's motion is refuted (confirmMotion()).
// Before either explanation is scored, the previous frame's levels are mapped to the current
// frame's (fitLevels): a frame brighter or darker as a whole would otherwise differ from both
// explanations everywhere, and the frame's median difference, the unit of the confirmation,
// would grow until no motion is confirmed (an alternating gain of 8 %: DAVIS cows J 0.79 -> 0.26).
// Three steps: the camera's fit needs the previous mask carried by the flow, so the previous frame
// is brought through the flow with it, in one pass over the flow's map, before the camera is
// known; the change of light is fitted to the frame and the previous one brought by the flow;
// the frame is compared once the camera's map is made.
class PhotometricCheck {
 public:
  // The previous frame (`previous_grey`, CV_8U) and its mask (`previous_mask`, CV_8U 0/255, of
  // the same size; may be empty) brought to the current frame through the flow's map
  // (flowMap()). `carried`: the mask interpolated (CV_8U), 0 where the flow leaves the previous
  // frame; empty without a mask.
  void followFlow(const cv::Mat& previous_grey, const cv::Mat& previous_mask,
                  const cv::Mat& flow_map, cv::Mat* carried);

  // The change of light from the previous frame followFlow() was last given to `grey` (CV_8U, the
  // current frame): least squares over every fourth row where neither frame clips (0 or 255),
  // between `grey` and the previous frame brought by the flow, which aligns the movers too. The
  // identity unless the gain lies within [0.5, 2] (two unrelated scenes, a cut, fit a gain near
  // their correlation, near 0) and the fitted map at least halves the median difference between
  // the two (over the same rows): then a change of light is most of what differs. Ordinary video
  // keeps the identity on every pair (DAVIS's 15 sequences: no pair), and its masks are those
  // made without the fit; a frame without a level of spread keeps it too.
  LevelMap fitLevels(const cv::Mat& grey) const;

  // The pair followFlow() was last given: `grey` (CV_8U) the current frame, the camera's map as
  // cameraMap() makes it, `levels` the pair's change of light (fitLevels()), `ignored` (CV_8U,
  // or empty) non-zero where the frame's median difference, the unit, must not look: a region
  // fixed to the camera differs under it everywhere. `confirmation`: CV_32F.
  void confirm(const cv::Mat& grey, const cv::Mat& camera_map, const LevelMap& levels,
               const cv::Mat& ignored, const Params& params, cv::Mat* confirmation);

 private:
  BilinearRemap previous_;       // the previous grey frame, its border replicated
  BilinearRemap previous_mask_;  // the previous mask, 0 around it
  BoxMean5 patch_mean_;
  cv::Mat by_flow_, by_camera_, flow_error_, camera_error_;
};

// Positive evidence scaled by the confirmation (CV_32F, [-1, 1]), no lower than `evidence_min`;
// negative evidence is kept. A residual whose motion the patch refutes (the camera explains it
// better than the flow, on texture the flow's displacement would have misaligned) says static
// as strongly as it said moving: DIS's flow bleeds from a mover onto the textured background
// beside it (the halo a carried mask then keeps, the gap between two movers close together)
// as it does onto flat background, where both explanations are alike and the residual says
// nothing (docs/design.md, "A refuted residual says static").
void confirmMotion(const cv::Mat& confirmation, const Params& params, cv::Mat* evidence);

// A pixel is uncovered when the previous frame's mover hid what the camera puts there (the
// previous mask, CV_8U 0/255, at the nearest pixel to `camera_map`'s, above half) while its flow
// does not lead back into the mover (`carried`, as PhotometricCheck::followFlow() carries it, under half).
// There the photometric check compares the frame with the mover that hid the background: the
// camera cannot explain the pixel, and a flow that DIS smeared from the mover, taking it to
// background further back, can. The previous frame holds nothing to confirm its motion with, so
// its positive evidence is dropped (negative kept). `uncovered`: 255 there, 0 elsewhere.
void uncoveredPixels(const cv::Mat& carried, const cv::Mat& previous_mask,
                     const cv::Mat& camera_map, cv::Mat* uncovered);
void dropUncovered(const cv::Mat& carried, const cv::Mat& previous_mask, const cv::Mat& camera_map,
                   cv::Mat* evidence);

// `evidence` plus what the carried mask says, into *with_memory: read as a probability p
// softened to [memory_floor, 1 - memory_floor], it weighs in as memory_weight * log(p / (1 - p)).
void addMemory(const cv::Mat& carried, const Params& params, const cv::Mat& evidence,
               cv::Mat* with_memory);

}  // namespace movseg
