// §3.2 feature classification: eq. (3) on the compensated difference, refined by the colour
// GMMs of eq. (5).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

// The threshold of eq. (3) for one difference image: max(lambda, lambda_residual_factor * q75)
// where q75 is the upper quartile of d at `static_points` (points believed to be background).
double chooseLambda(const cv::Mat& difference, const std::vector<cv::Point2f>& static_points,
                    const Params& params);

// Eq. (3): foreground where d > lambda, background otherwise (d sampled at each point).
std::vector<FeatureLabel> classifyByDifference(const cv::Mat& difference,
                                               const std::vector<cv::Point2f>& points,
                                               double lambda);

// Eq. (5): fits a GMM to the foreground and one to the background points' colours, then marks
// unknown every foreground point with P_f <= P_b and every background point with P_f >= P_b.
// Does nothing when either set is empty (there is nothing to compare against).
void refineByColour(const std::vector<cv::Vec3f>& colours, int clusters,
                    std::vector<FeatureLabel>* labels);

// §3.2 for one frame's features.
struct FeatureClasses {
  double lambda = 0;                        // the threshold of eq. (3) for this pair
  std::vector<FeatureLabel> by_difference;  // eq. (3)
  std::vector<FeatureLabel> labels;         // then eq. (5), when params.gmm_refine
};

// Classifies `points` of `bgr` (8-bit BGR) by the compensated difference `difference` (eq. 4,
// same size), with lambda chosen from d at `static_points`, and refines the labels by colour.
FeatureClasses classifyFeatures(const cv::Mat& difference, const cv::Mat& bgr,
                                const std::vector<cv::Point2f>& points,
                                const std::vector<cv::Point2f>& static_points,
                                const Params& params);

}  // namespace movseg
