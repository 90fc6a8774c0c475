// One RANSAC loop for every model, split as COLMAP splits it (src/colmap/optim/ransac.h): an
// Estimator fits models and measures residuals, a Sampler draws the minimal samples, a
// SupportMeasurer scores hypotheses; the loop keeps the best and refits it by least squares.
// A new model (a parallax model, say) is one more Estimator class:
//
//   struct Estimator {
//     using Model = ...;
//     static constexpr int kMinNumSamples = ...;
//     // Fits a model to the correspondences (exactly for a minimal sample, by least squares
//     // for more); false for a degenerate set.
//     static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
//                          Model* model);
//     // Squared residual of every correspondence, in squared pixels.
//     static void residuals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
//                           const Model& model, std::vector<double>* residuals);
//   };
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "motion/estimators.h"
#include "motion/spread_sampler.h"
#include "motion/support.h"

namespace movseg {

struct RansacOptions {
  int max_trials = 64;       // hypotheses at most (fewer once the inlier ratio allows)
  double max_error = 1.0;    // largest residual of an inlier, pixels
  double confidence = 0.99;  // of having drawn one all-inlier sample, for the adaptive trials
  int sample_grid = 3;       // the Sampler's grid side (SpreadSampler)

  // Throws std::invalid_argument naming the first option out of range.
  void check() const;
};

template <typename Model>
struct RansacReport {
  bool success = false;  // a model was fitted to at least kMinNumSamples inliers
  int trials = 0;        // minimal samples drawn
  Model model{};         // the refitted model, when success
  int num_inliers = 0;   // of `model`
  std::vector<char> inlier_mask;  // of `model`, per correspondence
};

template <typename Estimator, typename Sampler = SpreadSampler,
          typename SupportMeasurer = CoverageSupportMeasurer>
class Ransac {
 public:
  using Model = typename Estimator::Model;
  using Report = RansacReport<Model>;
  static constexpr int kMinNumSamples = Estimator::kMinNumSamples;

  explicit Ransac(const RansacOptions& options) : options_(options) { options_.check(); }

  // x[i] (previous frame) corresponds to y[i] (current frame); both lie in an image of
  // `image_size`. `initial`, when given, is scored before any sample is drawn (a warm start).
  Report estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                  cv::Size image_size, cv::RNG& rng, const Model* initial = nullptr) const {
    Report report;
    const int n = static_cast<int>(x.size());
    if (n < kMinNumSamples) return report;

    const SupportMeasurer measurer(x, image_size);
    Best best;
    if (initial != nullptr) consider(x, y, *initial, measurer, &best);
    const Sampler sampler(x, image_size, options_.sample_grid);
    std::vector<int> sample;
    std::vector<cv::Point2f> sx(kMinNumSamples), sy(kMinNumSamples);
    int needed = options_.max_trials;
    for (report.trials = 0; report.trials < needed; ++report.trials) {
      sampler.sample(kMinNumSamples, rng, &sample);
      for (int k = 0; k < kMinNumSamples; ++k) {
        sx[k] = x[static_cast<size_t>(sample[k])];
        sy[k] = y[static_cast<size_t>(sample[k])];
      }
      Model model;
      if (!Estimator::estimate(sx, sy, &model)) continue;
      if (consider(x, y, model, measurer, &best)) needed = trialsFor(best.support.num_inliers, n);
    }
    if (best.support.num_inliers < kMinNumSamples) return report;
    report.model = best.model;
    report.success = refit(x, y, &report.model);
    report.num_inliers = inliers(x, y, report.model, &report.inlier_mask);
    return report;
  }

 private:
  struct Best {
    typename SupportMeasurer::Support support;
    Model model{};
  };

  double maxSquaredError() const { return options_.max_error * options_.max_error; }

  // Keeps `model` when its support beats the best so far.
  bool consider(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                const Model& model, const SupportMeasurer& measurer, Best* best) const {
    Estimator::residuals(x, y, model, &residuals_);
    const auto support = measurer.evaluate(residuals_, maxSquaredError());
    if (!SupportMeasurer::better(support, best->support)) return false;
    *best = {support, model};
    return true;
  }

  // The inlier mask of `model` and the number of inliers.
  int inliers(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
              const Model& model, std::vector<char>* mask) const {
    Estimator::residuals(x, y, model, &residuals_);
    mask->resize(x.size());
    int count = 0;
    for (size_t i = 0; i < x.size(); ++i) count += (*mask)[i] = residuals_[i] <= maxSquaredError();
    return count;
  }

  // Least squares on the inliers, twice: the refit model may gain inliers the sample missed.
  // False when a round finds too few inliers to fit; a degenerate refit keeps the model.
  bool refit(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
             Model* model) const {
    std::vector<char> mask;
    std::vector<cv::Point2f> ix, iy;
    for (int round = 0; round < 2; ++round) {
      if (inliers(x, y, *model, &mask) < kMinNumSamples) return false;
      ix.clear();
      iy.clear();
      for (size_t i = 0; i < x.size(); ++i) {
        if (!mask[i]) continue;
        ix.push_back(x[i]);
        iy.push_back(y[i]);
      }
      Model fitted;
      if (!Estimator::estimate(ix, iy, &fitted)) return true;
      *model = fitted;
    }
    return true;
  }

  // Trials after which an all-inlier sample has been drawn with options_.confidence.
  int trialsFor(int num_inliers, int n) const {
    const double inlier_ratio = static_cast<double>(num_inliers) / n;
    const double all_inliers = std::pow(inlier_ratio, kMinNumSamples);
    if (all_inliers >= 1.0) return 1;
    const double trials = std::log(1 - options_.confidence) / std::log(1 - all_inliers);
    return static_cast<int>(std::min<double>(options_.max_trials, std::ceil(trials)));
  }

  RansacOptions options_;
  mutable std::vector<double> residuals_;  // scratch, reused across hypotheses
};

}  // namespace movseg
