#include "evidence/motion_evidence.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// A residual scale below this (pixels) is below what the flow resolves.
constexpr float kMinResidualScale = 0.1f;

float quantile(std::vector<float>& values, double q) {
  const auto k = values.begin() + static_cast<std::ptrdiff_t>(q * (values.size() - 1));
  std::nth_element(values.begin(), k, values.end());
  return *k;
}

}  // namespace

float residualScale(std::vector<float> sample_residuals, const Params& params) {
  if (sample_residuals.empty()) return kMinResidualScale;
  const float upper = quantile(sample_residuals, params.evidence_quantile);
  const float median = quantile(sample_residuals, 0.5);
  return std::max({upper, static_cast<float>(params.evidence_median_factor) * median,
                   kMinResidualScale});
}

void motionEvidence(const cv::Mat& residual, float scale, const Params& params, cv::Mat* evidence) {
  const auto gain = static_cast<float>(params.evidence_gain);
  const auto offset = static_cast<float>(params.evidence_offset);
  const auto low = static_cast<float>(params.evidence_min);
  const auto high = static_cast<float>(params.evidence_max);
  evidence->create(residual.size(), CV_32F);
  for (int y = 0; y < residual.rows; ++y) {
    const float* r = residual.ptr<float>(y);
    float* e = evidence->ptr<float>(y);
    for (int x = 0; x < residual.cols; ++x) {
      e[x] = std::clamp(gain * (r[x] / scale - offset), low, high);
    }
  }
}

void carryMask(const cv::Mat& previous_mask, const cv::Mat& flow, cv::Mat* carried) {
  cv::Mat map(flow.size(), CV_32FC2);
  for (int y = 0; y < flow.rows; ++y) {
    const auto* f = flow.ptr<cv::Vec2f>(y);
    auto* m = map.ptr<cv::Vec2f>(y);
    for (int x = 0; x < flow.cols; ++x) m[x] = cv::Vec2f(x + f[x][0], y + f[x][1]);
  }
  cv::remap(previous_mask, *carried, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar(0));
}

void addMemory(const cv::Mat& carried, const Params& params, cv::Mat* evidence) {  // log(p / (1 - p)) per 8-bit level of the carried mask, p softened towards one half.
  const auto floor = static_cast<float>(params.memory_floor);
  const auto weight = static_cast<float>(params.memory_weight);
  float logit[256];
  for (int level = 0; level < 256; ++level) {
    const float p = floor + (1 - 2 * floor) * static_cast<float>(level) / 255.f;
    logit[level] = weight * std::log(p / (1 - p));
  }
  for (int y = 0; y < carried.rows; ++y) {
    const uchar* c = carried.ptr<uchar>(y);
    float* e = evidence->ptr<float>(y);
    for (int x = 0; x < carried.cols; ++x) e[x] += logit[c[x]];
  }
}

}  // namespace movseg
