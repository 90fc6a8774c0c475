#include "motion/compensation.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "motion/model.h"
#include "motion/patch.h"
#include "motion/ransac.h"

namespace movseg {
namespace {

// Eq. (4) at the given points of `cur` only (3x3 patch mean), as the outer layer needs; `prev`
// and `cur` are 8-bit grey.
std::vector<float> compensatedDifferenceAt(const cv::Mat& prev, const cv::Mat& cur,
                                           const cv::Matx33d& model,
                                           const std::vector<cv::Point2f>& cur_points) {
  const cv::Matx33d inverse = model.inv();
  std::vector<float> d(cur_points.size());
  float a[9], b[9];
  for (size_t i = 0; i < cur_points.size(); ++i) {
    samplePatch(cur, cur_points[i], 3, a);
    samplePatch(prev, applyModel(inverse, cur_points[i]), 3, b);
    float sum = 0;
    for (int k = 0; k < 9; ++k) sum += (a[k] - b[k]) * (a[k] - b[k]);
    d[i] = sum / 9.f;
  }
  return d;
}

// Fewer background matches than this and a 6- or 8-parameter fit is not trusted.
constexpr int kMinMatches = 8;

template <typename Estimator>
RansacReport<cv::Matx33d> fitModel(const std::vector<Track>& matches, const std::vector<char>& use,
                                   cv::Size image_size, const cv::Matx33d* initial,
                                   const Params& params, cv::RNG& rng) {
  std::vector<cv::Point2f> x, y;
  for (size_t i = 0; i < matches.size(); ++i) {
    if (!use[i]) continue;
    x.push_back(matches[i].prev);
    y.push_back(matches[i].cur);
  }
  RansacOptions options;
  options.max_trials = params.ransac_iterations;
  options.max_error = params.ransac_threshold;
  options.sample_grid = params.ransac_grid;
  return Ransac<Estimator>(options).estimate(x, y, image_size, rng, initial);
}

RansacReport<cv::Matx33d> fitCameraModel(const std::vector<Track>& matches,
                                         const std::vector<char>& use, cv::Size image_size,
                                         const cv::Matx33d* initial, const Params& params,
                                         cv::RNG& rng) {
  if (params.motion_model == MotionModel::kHomography) {
    return fitModel<HomographyEstimator>(matches, use, image_size, initial, params, rng);
  }
  return fitModel<AffineEstimator>(matches, use, image_size, initial, params, rng);
}

// Every k-th point so that at most `count` remain; detectFeatures() lists corners by strength
// and edge points in raster order, so the subsample keeps the spread of both.
std::vector<cv::Point2f> evenSubsample(const std::vector<cv::Point2f>& points, int count) {
  if (static_cast<int>(points.size()) <= count) return points;
  std::vector<cv::Point2f> kept;
  const double step = static_cast<double>(points.size()) / count;
  for (int i = 0; i < count; ++i) kept.push_back(points[static_cast<size_t>(i * step)]);
  return kept;
}

// Eq. (3) on the matches: S_b = {d <= lambda}.
std::vector<char> splitBackground(const AlignmentFrame& prev, const AlignmentFrame& cur,
                                  const std::vector<Track>& matches, const cv::Matx33d& model,
                                  double lambda) {
  std::vector<cv::Point2f> points;
  for (const Track& t : matches) points.push_back(t.cur);
  const std::vector<float> d = compensatedDifferenceAt(prev.grey, cur.grey, model,
                                                       points);
  std::vector<char> background(matches.size());
  for (size_t i = 0; i < d.size(); ++i) background[i] = d[i] <= lambda;
  return background;
}

}  // namespace

MotionEstimate estimateCameraMotion(const AlignmentFrame& prev, const AlignmentFrame& cur,
                                    const cv::Matx33d& warm, const Params& params,
                                    std::uint64_t seed) {
  MotionEstimate result;
  result.model = warm;
  result.features = static_cast<int>(prev.features.size());
  const cv::Matx33d predicted = params.warm_start ? warm : cv::Matx33d::eye();
  const std::vector<Track> tracks = trackForwardBackward(
      prev.pyramid, cur.pyramid, evenSubsample(prev.features, params.max_tracked_features),
      predicted, params);
  result.tracks = static_cast<int>(tracks.size());
  result.matches = filterTracks(tracks);
  result.background.assign(result.matches.size(), 1);  // Algorithm 1: S_b = S_m
  if (static_cast<int>(result.matches.size()) < kMinMatches) {
    result.fallback = true;
    return result;
  }

  cv::RNG rng(seed);
  const cv::Size size = cur.grey.size();
  const cv::Matx33d* initial = params.warm_start ? &warm : nullptr;
  bool fitted = false;
  while (result.outer_iterations < params.max_outer_iterations) {
    ++result.outer_iterations;
    const RansacReport<cv::Matx33d> report =
        fitCameraModel(result.matches, result.background, size, initial, params, rng);  // step 1
    if (!report.success) break;
    result.model = report.model;
    fitted = true;
    std::vector<char> background =
        splitBackground(prev, cur, result.matches, result.model, params.lambda);  // steps 2-3
    const auto count = std::count(background.begin(), background.end(), 1);
    if (background == result.background || count < kMinMatches) break;  // step 4: stable
    result.background = std::move(background);
  }
  if (!fitted) {
    result.model = warm;
    result.fallback = true;
  }
  return result;
}

cv::Mat warpPrevious(const cv::Mat& prev, const cv::Mat& cur, const cv::Matx33d& model) {
  cv::Mat warped = cur.clone();  // BORDER_TRANSPARENT leaves these values where prev has none
  if (isAffine(model)) {
    cv::warpAffine(prev, warped, cv::Mat(model).rowRange(0, 2), cur.size(), cv::INTER_LINEAR,
                   cv::BORDER_TRANSPARENT);
  } else {
    cv::warpPerspective(prev, warped, cv::Mat(model), cur.size(), cv::INTER_LINEAR,
                        cv::BORDER_TRANSPARENT);
  }
  return warped;
}

cv::Mat compensatedDifference(const cv::Mat& prev, const cv::Mat& cur, const cv::Matx33d& model) {
  cv::Mat diff, squared, d;
  cv::absdiff(cur, warpPrevious(prev, cur, model), diff);
  diff.convertTo(diff, CV_32F);
  cv::multiply(diff, diff, squared);
  if (cur.channels() == 1) {
    d = squared;
  } else {
    cv::transform(squared, d, cv::Matx13f(1.f / 3, 1.f / 3, 1.f / 3));
  }
  return d;
}

}  // namespace movseg
