// §3.2 colour models: a Gaussian mixture with diagonal covariance whose components are the
// clusters of a farthest-point clustering (Gonzalez, ref. [17]), weighted by cluster share.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Gonzalez' farthest-point clustering: the first centre is samples[0], each next centre is the
// sample farthest from all centres so far; every sample joins its nearest centre. Returns the
// cluster of each sample (at most k clusters, fewer when there are fewer distinct samples).
std::vector<int> farthestPointClusters(const std::vector<cv::Vec3f>& samples, int k);

class ColourGmm {
 public:
  // Eq. (5)'s model of one feature set. An empty set gives an empty model.
  static ColourGmm fit(const std::vector<cv::Vec3f>& samples, int k);

  bool empty() const { return components_.empty(); }
  // log p(y) of eq. (5); -infinity for an empty model.
  double logLikelihood(const cv::Vec3f& colour) const;

 private:
  struct Component {
    double log_scale;  // log of the weight times the Gaussian's normalising constant
    cv::Vec3d mean;
    cv::Vec3d inv_variance;

    // log of the weighted density at `colour`.
    double logDensity(const cv::Vec3f& colour) const {
      double log_p = log_scale;
      for (int d = 0; d < 3; ++d) {
        const double diff = colour[d] - mean[d];
        log_p -= 0.5 * diff * diff * inv_variance[d];
      }
      return log_p;
    }
  };
  std::vector<Component> components_;
};

}  // namespace movseg
