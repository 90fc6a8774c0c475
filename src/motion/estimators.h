// Model estimators for the RANSAC loop (COLMAP's split): each knows its minimal sample size,
// how to fit a model to a minimal sample, how to fit one to many points by least squares, and
// its residuals. Models are 3x3 matrices mapping X (previous frame) to Y (current frame).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Eq. (1): the 6-parameter affine model (a1..a4, t1, t2).
struct AffineEstimator {
  static constexpr int kMinNumSamples = 3;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       cv::Matx33d* model);
};

// 8-parameter homography, for planar scenes under strong perspective.
struct HomographyEstimator {
  static constexpr int kMinNumSamples = 4;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       cv::Matx33d* model);
};

// Squared transfer error |model(x) - y|^2 of each correspondence; shared by both models.
void squaredResiduals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                      const cv::Matx33d& model, std::vector<double>* residuals);

}  // namespace movseg
