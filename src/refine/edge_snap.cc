#include "refine/edge_snap.h"

#include <algorithm>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "core/frame.h"

namespace movseg {
namespace {

// A window's mean label strictly between these holds both labels: the outline crosses it.
constexpr float kMixedLow = 1e-4f, kMixedHigh = 1.f - 1e-4f;

// What the filter did to a pixel at the working scale (bits, so that taps can be or-ed).
constexpr uchar kKept = 0, kChanged = 1, kThin = 2;

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
int reflected(int i, int n) {
  return i >= 0 && i < n ? i : cv::borderInterpolate(i, n, cv::BORDER_REFLECT);
}

// out[x] = (first[x] + first[x + 1] + ... + first[x + side - 1]) * scale, added left to right,
// four outputs at a time: each sum stays in a register (a pass over the row per term had
// cost twice the instructions).
void windowAcross(const float* first, int w, int side, float scale, float* out) {
  const cv::v_float32x4 scale_v = cv::v_setall_f32(scale);
  int x = 0;
  for (; x + 4 <= w; x += 4) {
    cv::v_float32x4 sum = cv::v_load(first + x);
    for (int d = 1; d < side; ++d) sum += cv::v_load(first + x + d);
    cv::v_store(out + x, sum * scale_v);
  }
  for (; x < w; ++x) {
    float sum = first[x];
    for (int d = 1; d < side; ++d) sum += first[x + d];
    out[x] = sum * scale;
  }
}

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
    // reflected(-d, w) and reflected(w - 1 + d, w), the image being wider than the radius.
    for (int d = 1; d <= radius; ++d) {
      column[-d] = column[d - 1];
      column[w - 1 + d] = column[w - d];
    }
    windowAcross(column - radius, w, side, scale, mean->ptr<float>(y));
    if (y + 1 == h) return;
    const float* leaving = src.ptr<float>(reflected(y - radius, h));
    const float* entering = src.ptr<float>(reflected(y + radius + 1, h));
    for (int x = 0; x < w; ++x) column[x] += entering[x] - leaving[x];
  }
}

// `*image` made a view of `size` into a buffer of `whole` size and `type`, the buffer of the last
// call reused: the outline's region changes size from frame to frame, its images' buffers do not.
void regionView(cv::Size whole, cv::Size size, int type, cv::Mat* image) {
  if (!image->empty()) image->adjustROI(whole.height, whole.height, whole.width, whole.width);
  image->create(whole, type);
  *image = (*image)(cv::Rect({0, 0}, size));
}

// One row of a 3x3 cross's erosion (Op std::min) or dilation (std::max): out[x] is the extreme
// of line[x], line[x + 1] and line[x + 2] (the row, one pixel past each end) and of above[x] and
// below[x].
template <const uchar& (*Op)(const uchar&, const uchar&)>
void crossRow(const uchar* above, const uchar* line, const uchar* below, int width, uchar* out) {
  for (int x = 0; x < width; ++x) {
    out[x] = Op(Op(Op(line[x], line[x + 2]), line[x + 1]), Op(above[x], below[x]));
  }
}

// cv::morphologyEx(mask(region), *opened, MORPH_OPEN) with a 3x3 cross, without the filter
// engines OpenCV builds (and allocates) on every call; min and max make it exact. As OpenCV's,
// the erosion reads the mask around the region (a region's parent image) and 255 past the
// mask's edges, the dilation 0 past the region's. `line`, `edge` and `eroded`: scratch.
void openWithCross(const cv::Mat& mask, cv::Rect region, std::vector<uchar>* line,
                   std::vector<uchar>* edge, cv::Mat* eroded, cv::Mat* opened) {
  const int w = region.width, h = region.height;
  line->resize(static_cast<size_t>(w) + 2);
  edge->assign(static_cast<size_t>(w), 255);
  for (int y = 0; y < h; ++y) {
    const int at = region.y + y;
    const uchar* row = mask.ptr<uchar>(at) + region.x;
    const uchar* above = at > 0 ? mask.ptr<uchar>(at - 1) + region.x : edge->data();
    const uchar* below = at + 1 < mask.rows ? mask.ptr<uchar>(at + 1) + region.x : edge->data();
    (*line)[0] = region.x > 0 ? row[-1] : 255;
    std::copy(row, row + w, line->data() + 1);
    (*line)[static_cast<size_t>(w) + 1] = region.x + w < mask.cols ? row[w] : 255;
    crossRow<std::min<uchar>>(above, line->data(), below, w, eroded->ptr<uchar>(y));
  }
  edge->assign(static_cast<size_t>(w), 0);
  for (int y = 0; y < h; ++y) {
    const uchar* row = eroded->ptr<uchar>(y);
    const uchar* above = y > 0 ? eroded->ptr<uchar>(y - 1) : edge->data();
    const uchar* below = y + 1 < h ? eroded->ptr<uchar>(y + 1) : edge->data();
    (*line)[0] = 0;
    std::copy(row, row + w, line->data() + 1);
    (*line)[static_cast<size_t>(w) + 1] = 0;
    crossRow<std::max<uchar>>(above, line->data(), below, w, opened->ptr<uchar>(y));
  }
}

// One row of the snapped mask: the filter's label, 255 * (slope * brightness + offset) as
// cv::saturate_cast<uchar> makes it, except where the opening removed the pixel (a thin part,
// kept); *state what the filter did. Sixteen pixels at a time: cvtps2dq rounds as cvRound
// does (to nearest even; INT_MIN beyond int's range, as cvRound), and the saturating packs to
// 16 then 8 bits clamp as saturate_cast does.
void snapRow(const float* brightness, const float* slope, const float* offset, const uchar* opened,
             int width, uchar* out, uchar* state) {
  const cv::v_float32x4 full = cv::v_setall_f32(255.f);
  const cv::v_uint8x16 thin_state = cv::v_setall_u8(kThin);
  const cv::v_uint8x16 changed_state = cv::v_setall_u8(kChanged);
  int x = 0;
  for (; x + 16 <= width; x += 16) {
    cv::v_int32x4 rounded[4];
    for (int k = 0; k < 4; ++k) {
      const int at = x + 4 * k;
      rounded[k] = cv::v_round(
          full * (cv::v_load(slope + at) * cv::v_load(brightness + at) + cv::v_load(offset + at)));
    }
    const cv::v_uint8x16 filtered =
        cv::v_pack_u(cv::v_pack(rounded[0], rounded[1]), cv::v_pack(rounded[2], rounded[3]));
    const cv::v_uint8x16 before = cv::v_load(out + x);
    const cv::v_uint8x16 thin = before != cv::v_load(opened + x);  // all ones where thin
    const cv::v_uint8x16 value = filtered | thin;
    cv::v_store(state + x, cv::v_select(thin, thin_state, (value != before) & changed_state));
    cv::v_store(out + x, value);
  }
  for (; x < width; ++x) {
    const bool thin = out[x] != opened[x];
    const uchar value =
        thin ? 255 : cv::saturate_cast<uchar>(255.f * (slope[x] * brightness[x] + offset[x]));
    state[x] = thin ? kThin : value != out[x] ? kChanged : kKept;
    out[x] = value;
  }
}

}  // namespace

cv::Mat EdgeSnap::snap(const cv::Mat& mask, const cv::Mat& grey, int radius,
                       const cv::Mat& output_grey) {
  CV_Assert(mask.type() == CV_8U && grey.type() == CV_8U && mask.size() == grey.size());
  CV_Assert(output_grey.empty() ||
            (output_grey.type() == CV_8U && output_grey.cols >= mask.cols &&
             output_grey.rows >= mask.rows));
  const cv::Rect region = radius > 0 ? outlineRegion(mask, radius) : cv::Rect();
  // A region narrower than a window is an image that small: its outline stays.
  if (region.width <= 2 * radius || region.height <= 2 * radius) {
    if (output_grey.empty()) return mask;
    scaledMask(mask, output_grey.size(), &finer_);
    return finer_;
  }
  for (cv::Mat* image : {&guide_, &square_, &label_, &masked_guide_, &mean_guide_, &mean_square_,
                         &mean_label_, &mean_masked_guide_, &slope_, &offset_, &mean_slope_,
                         &mean_offset_}) {
    regionView(mask.size(), region.size(), CV_32F, image);
  }
  for (cv::Mat* image : {&eroded_, &opened_, &state_}) {
    regionView(mask.size(), region.size(), CV_8U, image);
  }
  grey(region).convertTo(guide_, CV_32F);
  mask(region).convertTo(label_, CV_32F, 1.0 / 255);
  cv::multiply(guide_, guide_, square_);
  cv::multiply(guide_, label_, masked_guide_);
  windowMean(guide_, radius, &scratch_, &mean_guide_);
  windowMean(square_, radius, &scratch_, &mean_square_);
  windowMean(label_, radius, &scratch_, &mean_label_);
  windowMean(masked_guide_, radius, &scratch_, &mean_masked_guide_);
  // Each window's least-squares line label = slope * grey + offset, regularised by kRegulariser;
  // a window of one label keeps it (slope 0).
  for (int y = 0; y < guide_.rows; ++y) {
    const float* grey_mean = mean_guide_.ptr<float>(y);
    const float* square = mean_square_.ptr<float>(y);
    const float* label = mean_label_.ptr<float>(y);
    const float* masked = mean_masked_guide_.ptr<float>(y);
    float* slope = slope_.ptr<float>(y);
    float* offset = offset_.ptr<float>(y);
    for (int x = 0; x < guide_.cols; ++x) {
      const bool mixed = label[x] > kMixedLow && label[x] < kMixedHigh;
      const float variance = square[x] - grey_mean[x] * grey_mean[x];
      slope[x] = mixed ? (masked[x] - grey_mean[x] * label[x]) / (variance + kRegulariser) : 0.f;
      offset[x] = label[x] - slope[x] * grey_mean[x];
    }
  }
  windowMean(slope_, radius, &scratch_, &mean_slope_);
  windowMean(offset_, radius, &scratch_, &mean_offset_);
  // Parts of the mask narrower than a 3x3 cross (legs, poles, a mover's tip at the working
  // scale) are narrower than any window: the filter would average them away, so it does not
  // decide them.
  openWithCross(mask, region, &line_, &edge_, &eroded_, &opened_);
  mask.copyTo(snapped_);
  for (int y = 0; y < guide_.rows; ++y) {
    snapRow(guide_.ptr<float>(y), mean_slope_.ptr<float>(y), mean_offset_.ptr<float>(y),
            opened_.ptr<uchar>(y), guide_.cols, snapped_.ptr<uchar>(y + region.y) + region.x,
            state_.ptr<uchar>(y));
  }
  if (output_grey.empty() || output_grey.size() == mask.size()) return snapped_;
  return onFinerEdges(snapped_, region, output_grey);
}

cv::Mat EdgeSnap::onFinerEdges(const cv::Mat& snapped, cv::Rect region, const cv::Mat& fine) {
  cv::Mat& out = finer_;
  scaledMask(snapped, fine.size(), &out);
  // cv::resize's bilinear taps: output pixel x reads the region's columns x0 and x0 + 1, the
  // latter with weight (x + 0.5) * sx - 0.5 - region.x - x0, and likewise for rows. Pixels whose
  // taps leave the region keep `out` (the filter changed nothing near the region's edges).
  const double sx = static_cast<double>(snapped.cols) / fine.cols;
  const double sy = static_cast<double>(snapped.rows) / fine.rows;
  auto tap = [](int i, double scale, int origin) { return (i + 0.5) * scale - 0.5 - origin; };
  // first_[x0]: the first output column whose left tap is x0 or beyond.
  first_.assign(static_cast<size_t>(region.width), fine.cols);
  for (int x = fine.cols - 1; x >= 0; --x) {
    const int x0 = cvFloor(tap(x, sx, region.x));
    if (x0 >= 0 && x0 < region.width) first_[static_cast<size_t>(x0)] = x;
  }
  for (int x0 = region.width - 2; x0 >= 0; --x0) {
    first_[static_cast<size_t>(x0)] =
        std::min(first_[static_cast<size_t>(x0)], first_[static_cast<size_t>(x0 + 1)]);
  }
  changed_rows_.assign(static_cast<size_t>(region.height), false);
  for (int y = 0; y < region.height; ++y) {
    const uchar* state = state_.ptr<uchar>(y);
    changed_rows_[static_cast<size_t>(y)] =
        std::any_of(state, state + region.width, [](uchar s) { return s == kChanged; });
  }
  for (int y = 0; y < fine.rows; ++y) {
    const double at = tap(y, sy, region.y);
    const int y0 = cvFloor(at);
    if (y0 < 0 || y0 + 1 >= region.height ||
        !(changed_rows_[static_cast<size_t>(y0)] || changed_rows_[static_cast<size_t>(y0 + 1)])) {
      continue;
    }
    const float wy = static_cast<float>(at - y0);
    const uchar* state0 = state_.ptr<uchar>(y0);
    const uchar* state1 = state_.ptr<uchar>(y0 + 1);
    const float* slope0 = mean_slope_.ptr<float>(y0);
    const float* slope1 = mean_slope_.ptr<float>(y0 + 1);
    const float* offset0 = mean_offset_.ptr<float>(y0);
    const float* offset1 = mean_offset_.ptr<float>(y0 + 1);
    const uchar* nearest_row = wy < 0.5f ? state0 : state1;
    const uchar* brightness = fine.ptr<uchar>(y);
    uchar* row = out.ptr<uchar>(y);
    for (int x0 = 0; x0 + 1 < region.width; ++x0) {
      // Only where the filter changed a tap: elsewhere the scaled-up working result is the
      // filter's own.
      if (!((state0[x0] | state0[x0 + 1] | state1[x0] | state1[x0 + 1]) & kChanged)) continue;
      auto bilinear = [&](const float* top, const float* bottom, float wx) {
        const float upper = top[x0] + wx * (top[x0 + 1] - top[x0]);
        const float lower = bottom[x0] + wx * (bottom[x0 + 1] - bottom[x0]);
        return upper + wy * (lower - upper);
      };
      const int end = first_[static_cast<size_t>(x0 + 1)];
      for (int x = first_[static_cast<size_t>(x0)]; x < end; ++x) {
        const auto wx = static_cast<float>(tap(x, sx, region.x) - x0);
        if (nearest_row[wx < 0.5f ? x0 : x0 + 1] == kThin) continue;  // the thin part's own
        const float slope = bilinear(slope0, slope1, wx);
        const float offset = bilinear(offset0, offset1, wx);
        row[x] = cv::saturate_cast<uchar>(255.f * (slope * brightness[x] + offset));
      }
    }
  }
  return out;
}

}  // namespace movseg
