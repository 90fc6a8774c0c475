#include "classify/colour_gmm.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace movseg {
namespace {

// Variance floor, 8-bit units squared: a cluster of identical colours would otherwise have a
// zero variance and an infinite density (sensor noise alone is about this large).
constexpr double kMinVariance = 4.0;

// Farthest-point clustering makes outliers centres of their own; a colour seen at fewer points
// than this is not a mode of the set and gets no component (it would otherwise vouch for
// itself, e.g. keep a mislabelled point that has the other set's colour).
constexpr int kMinComponentSize = 3;

float squaredDistance(const cv::Vec3f& a, const cv::Vec3f& b) {
  const cv::Vec3f d = a - b;
  return d.dot(d);
}

}  // namespace

std::vector<int> farthestPointClusters(const std::vector<cv::Vec3f>& samples, int k) {
  std::vector<int> cluster(samples.size(), 0);
  if (samples.empty() || k <= 0) return cluster;
  std::vector<float> nearest(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) nearest[i] = squaredDistance(samples[i], samples[0]);
  for (int c = 1; c < k; ++c) {
    const auto farthest = std::max_element(nearest.begin(), nearest.end());
    if (*farthest <= 0.f) break;  // every sample coincides with a centre
    const cv::Vec3f centre = samples[static_cast<size_t>(farthest - nearest.begin())];
    for (size_t i = 0; i < samples.size(); ++i) {
      const float d = squaredDistance(samples[i], centre);
      if (d < nearest[i]) {
        nearest[i] = d;
        cluster[i] = c;
      }
    }
  }
  return cluster;
}

ColourGmm ColourGmm::fit(const std::vector<cv::Vec3f>& samples, int k) {
  ColourGmm gmm;
  if (samples.empty()) return gmm;
  const std::vector<int> cluster = farthestPointClusters(samples, k);
  const int clusters = *std::max_element(cluster.begin(), cluster.end()) + 1;
  std::vector<int> count(static_cast<size_t>(clusters), 0);
  std::vector<cv::Vec3d> sum(static_cast<size_t>(clusters)), sum_sq(static_cast<size_t>(clusters));
  for (size_t i = 0; i < samples.size(); ++i) {
    const auto c = static_cast<size_t>(cluster[i]);
    const cv::Vec3d s = samples[i];
    ++count[c];
    sum[c] += s;
    sum_sq[c] += s.mul(s);
  }
  const double log_two_pi = std::log(2 * CV_PI);
  const bool enough = *std::max_element(count.begin(), count.end()) >= kMinComponentSize;
  for (size_t c = 0; c < count.size(); ++c) {
    if (count[c] == 0 || (enough && count[c] < kMinComponentSize)) continue;
    Component comp;
    const double log_weight = std::log(static_cast<double>(count[c]) / samples.size());
    comp.mean = sum[c] / count[c];
    double log_norm = 0;  // log of the Gaussian's normalising constant
    for (int d = 0; d < 3; ++d) {
      const double variance =
          std::max(kMinVariance, sum_sq[c][d] / count[c] - comp.mean[d] * comp.mean[d]);
      comp.inv_variance[d] = 1.0 / variance;
      log_norm -= 0.5 * (log_two_pi + std::log(variance));
    }
    comp.log_scale = log_weight + log_norm;
    gmm.components_.push_back(comp);
  }
  return gmm;
}

double ColourGmm::logLikelihood(const cv::Vec3f& colour) const {
  // log-sum-exp over components: far colours would underflow a direct sum to 0 for both models.
  // Each term is worked out twice (for the largest, then for the sum), which costs less than
  // keeping them in an allocated list.
  double best = -std::numeric_limits<double>::infinity();
  for (const Component& comp : components_) best = std::max(best, comp.logDensity(colour));
  if (components_.empty()) return best;
  double sum = 0;
  for (const Component& comp : components_) {
    const double log_p = comp.logDensity(colour);
    sum += log_p == best ? 1.0 : std::exp(log_p - best);  // exp(0) is 1: no call for the largest
  }
  return best + std::log(sum);
}

}  // namespace movseg
