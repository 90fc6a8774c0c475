// Camera-model estimators for the RANSAC loop of motion/ransac.h (its header describes the
// interface): each knows its minimal sample size, how to fit a model to a minimal sample, how to
// fit one to many points by least squares, and its residuals. Models are 3x3 matrices mapping
// x (previous frame) to y (current frame); the residual is the squared transfer error
// |model(x) - y|^2.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Eq. (1): the 6-parameter affine model (a1..a4, t1, t2).
struct AffineEstimator {
  using Model = cv::Matx33d;
  static constexpr int kMinNumSamples = 3;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       Model* model);
  static void residuals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                        const Model& model, std::vector<double>* residuals);
};

// 8-parameter homography, for planar scenes under strong perspective.
struct HomographyEstimator {
  using Model = cv::Matx33d;
  static constexpr int kMinNumSamples = 4;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       Model* model);
  static void residuals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                        const Model& model, std::vector<double>* residuals);
};

}  // namespace movseg
