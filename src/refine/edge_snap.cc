#include "refine/edge_snap.h"

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// A window's mean label strictly between these holds both labels: the outline crosses it.
constexpr float kMixedLow = 1e-4f, kMixedHigh = 1.f - 1e-4f;

// The part of the image whose pixels the filter can change: the mask's bounding box grown by
// two window radii (a window mixing both labels, and the windows around its pixels), plus one
// so that a window reflected at the region's edge still sees only background. Empty when the
// mask is.
cv::Rect outlineRegion(const cv::Mat& mask, int radius) {
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return box;
  const int grow = 2 * radius + 1;
  const cv::Rect grown(box.x - grow, box.y - grow, box.width + 2 * grow, box.height + 2 * grow);
  return grown & cv::Rect(0, 0, mask.cols, mask.rows);
}

// An index reflected into [0, n) as BORDER_REFLECT does (the edge pixel repeated).
int reflected(int i, int n) { return cv::borderInterpolate(i, n, cv::BORDER_REFLECT); }

// The mean over each pixel's window of a CV_32F image, the window reflected at the borders (as
// cv::ximgproc::guidedFilter's). Column sums run down the image and each row's window sums
// across it, in floats, in loops the compiler vectorises: cv::boxFilter sums floats in doubles,
// and with it a whole snap took 0.46 ms against 0.26 (BM_EdgeSnap/0, one run, docs/design.md).
// Sums of integers under 2^24 are exact. The image must be at least a window wide
// and high.
void windowMean(const cv::Mat& src, int radius, std::vector<float>* scratch, cv::Mat* mean) {
  const int w = src.cols, h = src.rows, side = 2 * radius + 1;
  mean->create(src.size(), CV_32F);
  scratch->assign(static_cast<size_t>(w + 2 * radius), 0.f);  // column sums, padded
  float* column = scratch->data() + radius;
  for (int dy = -radius; dy <= radius; ++dy) {
    const float* in = src.ptr<float>(reflected(dy, h));
    for (int x = 0; x < w; ++x) column[x] += in[x];
  }
  const float scale = 1.f / static_cast<float>(side * side);
  for (int y = 0;; ++y) {
    for (int d = 1; d <= radius; ++d) {
      column[-d] = column[reflected(-d, w)];
      column[w - 1 + d] = column[reflected(w - 1 + d, w)];
    }
    float* out = mean->ptr<float>(y);
    const float* first = column - radius;
    for (int x = 0; x < w; ++x) out[x] = first[x];
    for (int d = 1; d < side; ++d) {
      for (int x = 0; x < w; ++x) out[x] += first[x + d];
    }
    for (int x = 0; x < w; ++x) out[x] *= scale;
    if (y + 1 == h) return;
    const float* leaving = src.ptr<float>(reflected(y - radius, h));
    const float* entering = src.ptr<float>(reflected(y + radius + 1, h));
    for (int x = 0; x < w; ++x) column[x] += entering[x] - leaving[x];
  }
}

}  // namespace

cv::Mat EdgeSnap::snap(const cv::Mat& mask, const cv::Mat& bgr, int radius) {
  CV_Assert(mask.type() == CV_8U && bgr.type() == CV_8UC3 && mask.size() == bgr.size());
  const cv::Rect region = radius > 0 ? outlineRegion(mask, radius) : cv::Rect();
  // A region narrower than a window is an image that small: its outline stays.
  if (region.width <= 2 * radius || region.height <= 2 * radius) return mask;
  cv::cvtColor(bgr(region), grey_, cv::COLOR_BGR2GRAY);
  grey_.convertTo(guide_, CV_32F);
  mask(region).convertTo(label_, CV_32F, 1.0 / 255);
  cv::multiply(guide_, guide_, square_);
  cv::multiply(guide_, label_, masked_guide_);
  windowMean(guide_, radius, &scratch_, &mean_guide_);
  windowMean(square_, radius, &scratch_, &mean_square_);
  windowMean(label_, radius, &scratch_, &mean_label_);
  windowMean(masked_guide_, radius, &scratch_, &mean_masked_guide_);
  // Each window's least-squares line label = slope * grey + offset, regularised by kRegulariser;
  // a window of one label keeps it (slope 0).
  slope_.create(guide_.size(), CV_32F);
  offset_.create(guide_.size(), CV_32F);
  for (int y = 0; y < guide_.rows; ++y) {
    const float* grey = mean_guide_.ptr<float>(y);
    const float* square = mean_square_.ptr<float>(y);
    const float* label = mean_label_.ptr<float>(y);
    const float* masked = mean_masked_guide_.ptr<float>(y);
    float* slope = slope_.ptr<float>(y);
    float* offset = offset_.ptr<float>(y);
    for (int x = 0; x < guide_.cols; ++x) {
      const bool mixed = label[x] > kMixedLow && label[x] < kMixedHigh;
      const float variance = square[x] - grey[x] * grey[x];
      slope[x] = mixed ? (masked[x] - grey[x] * label[x]) / (variance + kRegulariser) : 0.f;
      offset[x] = label[x] - slope[x] * grey[x];
    }
  }
  windowMean(slope_, radius, &scratch_, &mean_slope_);
  windowMean(offset_, radius, &scratch_, &mean_offset_);
  // Parts of the mask narrower than a 3x3 cross (legs, poles, a mover's tip at the working
  // scale) are narrower than any window: the filter would average them away, so it does not
  // decide them.
  cv::morphologyEx(mask(region), opened_, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_CROSS, {3, 3}));
  cv::Mat snapped = mask.clone();
  for (int y = 0; y < guide_.rows; ++y) {
    const float* grey = guide_.ptr<float>(y);
    const float* slope = mean_slope_.ptr<float>(y);
    const float* offset = mean_offset_.ptr<float>(y);
    const uchar* opened = opened_.ptr<uchar>(y);
    uchar* out = snapped.ptr<uchar>(y + region.y) + region.x;
    for (int x = 0; x < guide_.cols; ++x) {
      const bool thin = out[x] != opened[x];
      out[x] = thin ? 255 : cv::saturate_cast<uchar>(255.f * (slope[x] * grey[x] + offset[x]));
    }
  }
  return snapped;
}

}  // namespace movseg
