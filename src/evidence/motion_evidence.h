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

// Flow bleeds: where a patch is flat, DIS gives it the motion of its textured neighbour, and
// a residual alone cannot tell. The previous frame brought to the current one by the camera and
// by the flow answers it: where the camera explains the pixels as well as the flow does, there
// is no evidence of motion, however large the residual. Both explanations are scored by their
// mean absolute difference over a patch; the confirmation is how much the flow's is smaller, in
// units of `photometric_margin` times the frame's median difference under the camera (its
// noise, blur and gain change), clipped to [0, 1].
// Two steps: the camera's fit needs the previous mask carried by the flow, so the previous frame
// is brought through the flow with it, in one pass over the flow's map, before the camera is
// known; the frame is compared once the camera's map is made.
class PhotometricCheck {
 public:
  // The previous frame (`previous_grey`, CV_8U) and its mask (`previous_mask`, CV_8U 0/255, of
  // the same size; may be empty) brought to the current frame through the flow's map
  // (flowMap()). `carried`: the mask interpolated (CV_8U), 0 where the flow leaves the previous
  // frame; empty without a mask.
  void followFlow(const cv::Mat& previous_grey, const cv::Mat& previous_mask,
                  const cv::Mat& flow_map, cv::Mat* carried);

  // The pair followFlow() was last given: `grey` (CV_8U) the current frame, the camera's map as
  // cameraMap() makes it. `confirmation`: CV_32F.
  void confirm(const cv::Mat& grey, const cv::Mat& camera_map, const Params& params,
               cv::Mat* confirmation);

 private:
  BilinearRemap previous_;       // the previous grey frame, its border replicated
  BilinearRemap previous_mask_;  // the previous mask, 0 around it
  BoxMean5 patch_mean_;
  cv::Mat by_flow_, by_camera_, flow_error_, camera_error_;
};

// Positive evidence scaled by the confirmation (CV_32F, [0, 1]); negative evidence is kept.
void confirmMotion(const cv::Mat& confirmation, cv::Mat* evidence);

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
