// One RANSAC loop for every model, split as COLMAP splits it (src/colmap/optim/ransac.h): an
// Estimator fits models and measures residuals, a Sampler draws the minimal samples, a
// SupportMeasurer scores hypotheses; the loop keeps the best and refits it by least squares.
// A new model is one more Estimator class (as EpipoleEstimator was):
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

  // Storage for as many correspondences, so that calls with up to that many, however many each
  // has, allocate nothing.
  void reserve(size_t points) {
    report_.inlier_mask.reserve(points);
    measurer_.reserve(points);
    sampler_.reserve(points);
    residuals_.reserve(points);
    mask_.reserve(points);
    ix_.reserve(points);
    iy_.reserve(points);
  }

  // x[i] corresponds to y[i] (previous and current frame for paper; current and previous for
  // dense's flow); both lie in an image of `image_size`. `initial`, when given, is scored
  // before any sample is drawn (a warm start).
  // The report is the loop's own, valid until the next call: its buffers, and the sampler's
  // and the measurer's, are reused, so that a Ransac kept from frame to frame allocates nothing
  // once it has seen as many points.
  const Report& estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                         cv::Size image_size, cv::RNG& rng, const Model* initial = nullptr) {
    Report& report = report_;
    report.success = false;
    report.trials = 0;
    report.model = Model{};
    report.num_inliers = 0;
    report.inlier_mask.clear();
    const int n = static_cast<int>(x.size());
    if (n < kMinNumSamples) return report;

    measurer_.reset(x, image_size);
    Best best;
    if (initial != nullptr) consider(x, y, *initial, &best);
    sampler_.reset(x, image_size, options_.sample_grid);
    int needed = options_.max_trials;
    for (report.trials = 0; report.trials < needed; ++report.trials) {
      sampler_.sample(kMinNumSamples, rng, &sample_);
      for (int k = 0; k < kMinNumSamples; ++k) {
        sx_[k] = x[static_cast<size_t>(sample_[k])];
        sy_[k] = y[static_cast<size_t>(sample_[k])];
      }
      Model model;
      if (!Estimator::estimate(sx_, sy_, &model)) continue;
      if (consider(x, y, model, &best)) needed = trialsFor(best.support.num_inliers, n);
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
                const Model& model, Best* best) {
    Estimator::residuals(x, y, model, &residuals_);
    const auto support = measurer_.evaluate(residuals_, maxSquaredError());
    if (!SupportMeasurer::better(support, best->support)) return false;
    *best = {support, model};
    return true;
  }

  // The inlier mask of `model` and the number of inliers.
  int inliers(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
              const Model& model, std::vector<char>* mask) {
    Estimator::residuals(x, y, model, &residuals_);
    mask->resize(x.size());
    int count = 0;
    for (size_t i = 0; i < x.size(); ++i) count += (*mask)[i] = residuals_[i] <= maxSquaredError();
    return count;
  }

  // Least squares on the inliers, twice: the refit model may gain inliers the sample missed.
  // False when a round finds too few inliers to fit; a degenerate refit keeps the model.
  bool refit(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
             Model* model) {
    for (int round = 0; round < 2; ++round) {
      if (inliers(x, y, *model, &mask_) < kMinNumSamples) return false;
      ix_.clear();
      iy_.clear();
      for (size_t i = 0; i < x.size(); ++i) {
        if (!mask_[i]) continue;
        ix_.push_back(x[i]);
        iy_.push_back(y[i]);
      }
      Model fitted;
      if (!Estimator::estimate(ix_, iy_, &fitted)) return true;
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
  Report report_;
  // Scratch, reused across hypotheses and calls.
  SupportMeasurer measurer_;
  Sampler sampler_;
  std::vector<int> sample_;
  std::vector<cv::Point2f> sx_ = std::vector<cv::Point2f>(kMinNumSamples);
  std::vector<cv::Point2f> sy_ = std::vector<cv::Point2f>(kMinNumSamples);
  std::vector<double> residuals_;
  std::vector<char> mask_;            // refit()'s inliers
  std::vector<cv::Point2f> ix_, iy_;  // and their correspondences
};

}  // namespace movseg
