#include "motion/tracking.h"

#include "motion/model.h"
#include "motion/patch.h"

#include <algorithm>
#include <cmath>

#include <opencv2/video/tracking.hpp>

namespace movseg {
namespace {

template <typename T>
T median(std::vector<T> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

std::vector<Track> trackForwardBackward(const std::vector<cv::Mat>& prev_pyramid,
                                        const std::vector<cv::Mat>& cur_pyramid,
                                        const std::vector<cv::Point2f>& points,
                                        const cv::Matx33d& predicted, const Params& params) {
  std::vector<Track> tracks;
  if (points.empty() || prev_pyramid.empty() || cur_pyramid.empty()) return tracks;

  const cv::Size window(params.lk_window, params.lk_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.03);
  std::vector<cv::Point2f> forward(points.size()), backward = points;
  std::transform(points.begin(), points.end(), forward.begin(),
                 [&](cv::Point2f p) { return applyModel(predicted, p); });
  std::vector<uchar> ok_forward, ok_backward;
  // Not read, but asked for: OpenCV's tracks differ without it on some frames (docs/design.md,
  // "Speed of paper").
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(prev_pyramid, cur_pyramid, points, forward, ok_forward, error, window,
                           params.lk_levels, stop, cv::OPTFLOW_USE_INITIAL_FLOW);
  cv::calcOpticalFlowPyrLK(cur_pyramid, prev_pyramid, forward, backward, ok_backward, error,
                           window, params.lk_levels, stop, cv::OPTFLOW_USE_INITIAL_FLOW);

  const cv::Mat& prev = prev_pyramid[0];
  const cv::Mat& cur = cur_pyramid[0];
  const cv::Rect2f inside(0, 0, static_cast<float>(cur.cols - 1), static_cast<float>(cur.rows - 1));
  tracks.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!ok_forward[i] || !ok_backward[i] || !inside.contains(forward[i])) continue;
    Track t;
    t.prev = points[i];
    t.cur = forward[i];
    t.fb_distance = static_cast<float>(cv::norm(points[i] - backward[i]));
    t.zncc = zncc(prev, t.prev, cur, t.cur, params.zncc_window);
    tracks.push_back(t);
  }
  return tracks;
}

float zncc(const cv::Mat& image_a, cv::Point2f a, const cv::Mat& image_b, cv::Point2f b,
           int window) {
  const int n = window * window;
  std::vector<float> buffer(2 * static_cast<size_t>(n));
  float* pa = buffer.data();
  float* pb = pa + n;
  samplePatch(image_a, a, window, pa);
  samplePatch(image_b, b, window, pb);
  double sum_a = 0, sum_b = 0;
  for (int i = 0; i < n; ++i) sum_a += pa[i], sum_b += pb[i];
  const double mean_a = sum_a / n, mean_b = sum_b / n;
  double cross = 0, energy_a = 0, energy_b = 0;
  for (int i = 0; i < n; ++i) {
    const double da = pa[i] - mean_a, db = pb[i] - mean_b;
    cross += da * db;
    energy_a += da * da;
    energy_b += db * db;
  }
  const double energy = energy_a * energy_b;
  if (energy <= 1e-12) return 0.0f;
  return static_cast<float>(cross / std::sqrt(energy));
}

std::vector<Track> filterTracks(const std::vector<Track>& tracks) {
  if (tracks.empty()) return {};
  std::vector<float> scores, distances;
  for (const Track& t : tracks) {
    scores.push_back(t.zncc);
    distances.push_back(t.fb_distance);
  }
  const float eta1 = median(scores), eta2 = median(distances);
  std::vector<Track> kept;
  std::copy_if(tracks.begin(), tracks.end(), std::back_inserter(kept),
               [&](const Track& t) { return t.zncc >= eta1 && t.fb_distance <= eta2; });
  return kept;
}

}  // namespace movseg
