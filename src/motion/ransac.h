// One RANSAC loop for every model (COLMAP's split): the Estimator fits and scores models, the
// sampler (SpreadSampler) chooses the minimal samples, the support measure ranks hypotheses,
// and this loop keeps the best one and refits it by least squares on its inliers.
#pragma once

#include <algorithm>
#include <bitset>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "motion/estimators.h"
#include "motion/spread_sampler.h"

namespace movseg {

struct RansacOptions {
  int max_trials = 64;       // hypotheses at most (fewer when the inlier ratio allows)
  double max_error = 1.0;    // inlier transfer error, pixels
  double confidence = 0.99;  // for the adaptive number of trials
  int grid = 3;              // SpreadSampler grid side
};

// Support of a hypothesis: first how much of the image its inliers cover (occupied cells of a
// kCoverageGrid x kCoverageGrid grid), then how many there are. The background spans the image
// while a moving object is local, so coverage keeps a densely textured object from winning on
// numbers alone (docs/design.md).
struct SpreadSupport {
  static constexpr int kCoverageGrid = 8;
  int cells = 0;
  int inliers = 0;
  bool operator>(const SpreadSupport& o) const {
    return cells != o.cells ? cells > o.cells : inliers > o.inliers;
  }
};

struct RansacReport {
  bool success = false;
  int trials = 0;
  int support = 0;                 // inliers of the final model
  std::vector<char> inlier_mask;   // per correspondence
  cv::Matx33d model = cv::Matx33d::eye();
};

template <typename Estimator>
class Ransac {
 public:
  explicit Ransac(const RansacOptions& options) : options_(options) {}

  // `initial`, when given, is scored before any sample is drawn (the warm start).
  RansacReport estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                        cv::Size image_size, cv::RNG& rng,
                        const cv::Matx33d* initial = nullptr) const {
    RansacReport report;
    const int n = static_cast<int>(x.size());
    if (n < Estimator::kMinNumSamples) return report;

    coverageCells(x, image_size);
    SpreadSupport best;
    if (initial != nullptr) consider(x, y, *initial, &best, &report);
    const SpreadSampler sampler(x, image_size, options_.grid);
    std::vector<int> sample;
    std::vector<cv::Point2f> sx(Estimator::kMinNumSamples), sy(Estimator::kMinNumSamples);
    int needed = options_.max_trials;
    for (report.trials = 0; report.trials < needed; ++report.trials) {
      sampler.sample(Estimator::kMinNumSamples, rng, &sample);
      for (int k = 0; k < Estimator::kMinNumSamples; ++k) {
        sx[k] = x[static_cast<size_t>(sample[k])];
        sy[k] = y[static_cast<size_t>(sample[k])];
      }
      cv::Matx33d model;
      if (!Estimator::estimate(sx, sy, &model)) continue;
      if (consider(x, y, model, &best, &report)) needed = trialsFor(best.inliers, n);
    }
    if (report.support < Estimator::kMinNumSamples) return report;
    refit(x, y, &report);
    report.success = report.support >= Estimator::kMinNumSamples;
    return report;
  }

 private:
  void coverageCells(const std::vector<cv::Point2f>& x, cv::Size image_size) const {
    constexpr int g = SpreadSupport::kCoverageGrid;
    cells_.resize(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
      const int cx = std::clamp(static_cast<int>(x[i].x * g / image_size.width), 0, g - 1);
      const int cy = std::clamp(static_cast<int>(x[i].y * g / image_size.height), 0, g - 1);
      cells_[i] = cy * g + cx;
    }
  }

  // Keeps `model` when its support beats the best so far.
  bool consider(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                const cv::Matx33d& model, SpreadSupport* best, RansacReport* report) const {
    squaredResiduals(x, y, model, &residuals_);
    const double limit = options_.max_error * options_.max_error;
    std::bitset<SpreadSupport::kCoverageGrid * SpreadSupport::kCoverageGrid> covered;
    SpreadSupport support;
    for (size_t i = 0; i < residuals_.size(); ++i) {
      if (residuals_[i] > limit) continue;
      ++support.inliers;
      covered.set(static_cast<size_t>(cells_[i]));
    }
    support.cells = static_cast<int>(covered.count());
    if (!(support > *best)) return false;
    *best = support;
    report->support = support.inliers;
    report->model = model;
    return true;
  }

  // Least squares on the inliers, twice: the refit model may gain inliers the sample missed.
  void refit(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
             RansacReport* report) const {
    const double limit = options_.max_error * options_.max_error;
    for (int round = 0; round < 2; ++round) {
      squaredResiduals(x, y, report->model, &residuals_);
      std::vector<cv::Point2f> ix, iy;
      report->inlier_mask.assign(x.size(), 0);
      for (size_t i = 0; i < x.size(); ++i) {
        if (residuals_[i] > limit) continue;
        report->inlier_mask[i] = 1;
        ix.push_back(x[i]);
        iy.push_back(y[i]);
      }
      report->support = static_cast<int>(ix.size());
      cv::Matx33d model;
      if (report->support < Estimator::kMinNumSamples || !Estimator::estimate(ix, iy, &model)) {
        return;
      }
      report->model = model;
    }
  }

  int trialsFor(int support, int n) const {
    const double inlier_ratio = static_cast<double>(support) / n;
    const double all_inliers = std::pow(inlier_ratio, Estimator::kMinNumSamples);
    if (all_inliers >= 1.0) return 1;
    const double trials = std::log(1 - options_.confidence) / std::log(1 - all_inliers);
    return static_cast<int>(std::min<double>(options_.max_trials, std::ceil(trials)));
  }

  RansacOptions options_;
  mutable std::vector<double> residuals_;
  mutable std::vector<int> cells_;
};

}  // namespace movseg
