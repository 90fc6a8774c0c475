// The camera motion of a pair from its dense flow: a homography fitted by RANSAC (motion/ransac.h)
// to the flow at a grid of textured pixels, leaving out those believed to move, and what it
// leaves unexplained — the residual motion — at every pixel.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "motion/estimators.h"
#include "motion/ransac.h"
#include "motion/support.h"
#include "movseg/params.h"

namespace movseg {

struct FlowCamera {
  cv::Matx33d model = cv::Matx33d::eye();  // current -> previous frame, working pixels
  std::vector<cv::Point2f> at;             // the samples: pixels of the current frame,
  std::vector<cv::Point2f> to;             // where the flow takes them in the previous one,
  std::vector<char> background;            // and whether each was believed static
  bool fallback = false;                   // too few samples or no fit: identity
  // Plane + parallax: when the static scene beyond the model's plane shows depth, the epipole
  // (homogeneous, previous frame) that its residual motion points along.
  std::optional<cv::Vec3d> epipole;
  // Whether a rule that asks a share of the off-plane samples to move with the plane read it (a
  // mover the camera follows moves against the plane, all of it, so such a reading cannot be
  // one).
  bool depth_with_the_plane = false;
};

// A pixel the camera is fitted at, and its texture.
struct GridSample {
  cv::Point at;
  float texture;
};

// Every `step` pixels of `grey` (CV_8U, the current frame), with their minEigenValueAt, into
// `samples`, none where `ignored` (CV_8U of grey's size, or empty) is non-zero. Needs the frame
// alone, so it is made with the flow, before the previous mask is known.
void gridSamples(const cv::Mat& grey, int step, const cv::Mat& ignored,
                 std::vector<GridSample>* samples);

// The camera of a stream's pairs, in buffers kept from one pair to the next, its RANSACs' among
// them: at a fixed frame size a fit allocates nothing once a few pairs have been fitted.
class FlowCameraFitter {
 public:
  explicit FlowCameraFitter(const Params& params);

  // Samples `flow` (CV_32FC2, current -> previous) at the `grid` samples whose texture is above
  // its lower `params.flow_texture_quantile` — flat pixels carry no flow information — and fits
  // a homography to those not marked in `moving` (CV_8U, above 127; may be empty), unless that
  // would leave too few. With `params.static_camera` the model stays the identity. With
  // `params.parallax`, then the epipole, when enough of those samples are off the plane (more
  // than twice the inlier distance) and most of them agree on one. `previous_model`, the last
  // pair's when there is one (else null), is scored before any sample is drawn (a warm start,
  // as the paper's camera fit has): a camera's motion changes little from one pair to the next.
  // Written over `camera`, whose vectors are reused.
  void fit(const cv::Mat& flow, const std::vector<GridSample>& grid, const cv::Mat& moving,
           cv::RNG& rng, const cv::Matx33d* previous_model, FlowCamera* camera);

 private:
  // Sets camera->epipole and depth_with_the_plane.
  void findEpipole(cv::Size size, cv::RNG& rng, FlowCamera* camera);

  Params params_;
  RansacOptions options_;
  Ransac<HomographyEstimator> homography_;
  Ransac<EpipoleEstimator> epipole_;
  CoverageSupportMeasurer coverage_;
  // Scratch: the samples' textures, the correspondences given to a RANSAC, the off-plane
  // samples' steps with the plane and their residuals to the epipole.
  std::vector<float> textures_;
  std::vector<cv::Point2f> x_, y_, plane_step_;
  std::vector<double> residuals_;
};

// The smaller eigenvalue of the structure tensor over the 5x5 window at `p` of `grey` (CV_8U),
// as cv::cornerMinEigenVal(grey, _, 5) gives it there: 3x3 Sobel gradients, reflected borders.
// Computed at the samples alone, a sixtieth of the pixels at the default step.
float minEigenValueAt(const cv::Mat& grey, cv::Point p);

// The motion the static scene does not explain at every pixel (CV_32F): |p + flow(p) - s(p)|,
// where `flow_map` holds p + flow(p) and `camera_map` s(p), the static scene's explanation of
// p: model(p) as cameraMap() makes it, or with an epipole that point moved along its epipolar
// line (alongEpipolarLines()), which leaves the residual's part across the line.
void residualMotion(const cv::Mat& flow_map, const cv::Mat& camera_map, cv::Mat* residual);

// Where each pixel of the current frame came from in the previous one (CV_32FC2, for
// cv::remap): p + flow(p) by the flow, model(p) by the camera.
void flowMap(const cv::Mat& flow, cv::Mat* map);
void cameraMap(const cv::Matx33d& model, cv::Size size, cv::Mat* map);

// A static scene with depth explains a pixel's flow by any point of its epipolar line: each
// point model(p) of `camera_map` (CV_32FC2, as cameraMap() makes it) moved along the line
// through it and `epipole` (homogeneous) to the point nearest p + flow(p) (`flow_map`), in
// place. At the epipole itself, where the line has no direction, model(p) stays.
void alongEpipolarLines(const cv::Mat& flow_map, const cv::Vec3d& epipole, cv::Mat* camera_map);

// residualMotion() at the samples of `camera`, into `residuals`.
void residualAtSamples(const FlowCamera& camera, std::vector<float>* residuals);

}  // namespace movseg
