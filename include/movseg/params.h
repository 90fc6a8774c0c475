// movseg — moving object segmentation for freely moving cameras.
// Every parameter of the method, with the paper's names where it has one
// (Automatic Moving Object Segmentation for Freely Moving Cameras, 2014; "§" refers to it).
#pragma once

#include <cstdint>

namespace movseg {

// The frame-to-frame camera model of §3.1 (eq. 1). The paper uses an affine model; a
// homography suits planar scenes seen under strong perspective.
enum class MotionModel { kAffine, kHomography };

struct Params {
  // ---- §3.1 camera motion compensation ---------------------------------------------------
  // Skip alignment altogether (static camera, §4.1): the model is the identity.
  bool static_camera = false;
  // Camera model fitted by RANSAC.
  MotionModel motion_model = MotionModel::kAffine;
  // Alignment runs on the frame scaled to this width (§4.1 recommends 320x240); the model is
  // scaled back to full resolution. 0 = native size. Never upscales.
  int alignment_width = 320;
  // Corner features (Shi–Tomasi, ref. [15]) per frame, at the alignment scale.
  int max_corners = 500;
  // Edge features: in every cell of this many pixels (alignment scale) the pixel of strongest
  // gradient, when it is a clear edge, so that textured regions do not hog the features.
  int edge_cell = 4;
  // At most this many of the features are tracked for alignment (an even subsample; all of
  // them are classified in §3.2): a 6-parameter model needs a few hundred good tracks, and LK
  // is the stage's main cost.
  int max_tracked_features = 300;
  // Pyramid Lucas–Kanade (ref. [16]): window side and pyramid levels above the base.
  int lk_window = 11;
  int lk_levels = 3;
  // ZNCC window side t of eq. (2). Tracks with ZNCC < eta1 are dropped; eta1 is the median
  // ZNCC of the pair's tracks (the paper's rule). Likewise eta2 = median forward–backward
  // distance, tracks farther than eta2 are dropped.
  int zncc_window = 11;
  // RANSAC (inner layer of Algorithm 1): hypotheses per call, inlier distance in pixels at the
  // alignment scale, and the side of the coarse grid whose distinct cells the 3 (affine) or
  // 4 (homography) samples are drawn from.
  int ransac_iterations = 64;
  double ransac_threshold = 1.0;
  int ransac_grid = 3;
  // Outer layer of Algorithm 1: stop when the background set is stable or after this many.
  int max_outer_iterations = 5;
  // Start each pair from the previous pair's model (§4.1 speed-up): it predicts where LK looks
  // for each feature and is RANSAC's first hypothesis.
  bool warm_start = true;
  // Seed of every random choice; equal seeds give bit-identical masks.
  std::uint64_t seed = 0;

  // ---- §3.2 feature classification -----------------------------------------------------
  // lambda of eq. (3): a point is foreground when the compensated difference d (eq. 4, here the
  // mean squared difference over the colour channels, 8-bit units) exceeds
  //   max(lambda, lambda_residual_factor * q75),
  // q75 being the upper quartile of d at the background matches S_b: a floor, raised where the
  // alignment leaves residuals on static texture (parallax, blur, compression; docs/design.md).
  double lambda = 100.0;
  double lambda_residual_factor = 4.0;
  // Gaussian blur (sigma, segmentation-scale pixels) of both frames before eq. (4): sub-pixel
  // misalignment on fine texture and sensor noise then no longer look like motion. 0 = none.
  double difference_blur = 0.0;
  // K of eq. (5): clusters of each colour GMM, built by farthest-point clustering.
  int gmm_clusters = 5;
  // Refine F_f / F_b with the colour GMMs (eq. 5); off = plain eq. (3) classification.
  bool gmm_refine = true;

  // ---- §3.3 geodesic graph cut ---------------------------------------------------------
  // lambda of eq. (6): weight of the pairwise term against the unary term.
  double cut_weight = 1.0;
  // Colour term of the geodesic metric: a step costs sqrt(1 + (gamma * |dC|)^2) pixels with
  // colours in [0, 1] (docs/design.md).
  double geodesic_gamma = 150.0;
  // Max-flow only near the boundary of the geodesic labelling (D_F < D_B): pixels farther than
  // this (segmentation-scale pixels) keep that label. 0 = the whole image (the exact minimum).
  int cut_band = 8;
  // The geodesic distances and the cut run on the frame scaled to this width; the mask is
  // scaled back to full resolution. 0 = native size. Never upscales.
  int segmentation_width = 320;

  // ---- diagnostics -----------------------------------------------------------------------
  // Fill Result::debug with each stage's pictures (costs time; off by default).
  bool debug_images = false;

  // Throws std::invalid_argument naming the first parameter out of range.
  void check() const;
};

}  // namespace movseg
