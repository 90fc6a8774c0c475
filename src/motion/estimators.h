// Camera-model estimators for the RANSAC loop of motion/ransac.h (its header describes the
// interface): each knows its minimal sample size, how to fit a model to a minimal sample, how to
// fit one to many points by least squares, and its residuals. Camera models (affine,
// homography) are 3x3 matrices mapping x to y, with the squared transfer error |model(x) - y|^2
// as residual; EpipoleEstimator's model is a point (below).
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

// The epipole of a static 3-D scene after its dominant plane is removed (plane + parallax):
// x is where the plane's homography puts a point, y where it really is; for a static point the
// two lie on one line with the epipole (homogeneous, so that a camera translating sideways puts
// it at infinity). The residual is the squared distance of y from the line through x and the
// epipole, the part of the parallax no depth can explain. Degenerate for a pair of parallel
// displacements on one line, or when x and y coincide.
struct EpipoleEstimator {
  using Model = cv::Vec3d;
  static constexpr int kMinNumSamples = 2;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       Model* model);
  static void residuals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                        const Model& model, std::vector<double>* residuals);
  // The same for one point: |y - x| across the direction from the epipole to x.
  static double offLine(const cv::Point2f& x, const cv::Point2f& y, const Model& epipole);
};

// The unit eigenvector of the smallest eigenvalue of the symmetric `m`, to the bit as cv::eigen
// gives it where OpenCV is built with Eigen, without allocating; false when the solver fails.
// The least-squares fits' (3x3 for the epipole, 9x9 for the homography).
bool smallestEigenvector(const cv::Matx33d& m, cv::Vec3d* vector);
bool smallestEigenvector(const cv::Matx<double, 9, 9>& m, cv::Vec<double, 9>* vector);

}  // namespace movseg
