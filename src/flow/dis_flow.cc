#include "flow/dis_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// The FAST preset's patches and OpenCV's constants around them.
constexpr int kPatch = 8;          // a patch's side: one row is two vectors of four floats
constexpr int kPatchStride = 4;    // between patches
constexpr int kDescentSteps = 8;   // 16 gradient-descent iterations over the two passes
constexpr int kBorder = 16;        // replicated around the second image, where patches may land
constexpr int kStripes = 8;        // OpenCV searches 8 bands of patch rows; propagation stays in
                                   // each (its results then do not depend on the thread count)
constexpr float kPatchArea = kPatch * kPatch;
constexpr float kEps = 0.001f;     // OpenCV's EPS: a tensor's least determinant, a margin
constexpr float kInf = 1e10f;      // OpenCV's INF: no SSD yet

// The pyramid levels OpenCV 4.6's DIS searches, from `finest` to `coarsest`: it starts where a
// quarter of the larger side's motion is reachable, but at no level where a patch would not fit.
struct Scales {
  int finest, coarsest;
};

Scales searchedScales(cv::Size size, int finest) {
  const double reach = std::max(size.width, size.height) / (4.0 * kPatch);
  const int fits = std::min(size.width, size.height) / kPatch;
  const int deepest = static_cast<int>(std::log(static_cast<double>(fits)) / std::log(2.0));
  const int coarsest = std::min(static_cast<int>(std::log(reach) / std::log(2.0) + 0.5), deepest);
  if (coarsest >= finest) return {finest, coarsest};
  // A frame too small for the finest scale asked (under ~46 pixels on its longer side at scale 1)
  // gets the scales OpenCV then picks from its width (after Kroeger's code). OpenCV also keeps
  // that finest scale for the frames after; this does not.
  const float ratio = 2.0f * static_cast<float>(size.width) / (5.0f * kPatch);
  const int picked = std::max(0, static_cast<int>(std::floor(std::log2(ratio))));
  return {std::max(picked - 2, 0), picked};
}

using cv::v_float32x4;
using cv::v_int32x4;

// ---- how cv::resize (INTER_LINEAR, float) weighs its source -----------------------------------
// The flow is taken from one level to the next, the initial flow to each level and the finest
// level's flow to the frame's size as OpenCV's DIS does it, with cv::resize; these reproduce its
// arithmetic, at single pixels where only those are read.

// Along x, the source index is clamped with its weight set to 0, and past the last pixel only
// one tap is taken (the source value itself).
ResizeTaps tapsAlongX(int d, int source, int destination) {
  const double scale = 1.0 / (static_cast<double>(destination) / source);
  float f = static_cast<float>((d + 0.5) * scale - 0.5);
  int s = cvFloor(f);
  f -= static_cast<float>(s);
  if (s < 0) f = 0, s = 0;
  if (s >= source - 1) return {source - 1, source - 1, 1.0f, 0.0f};
  return {s, s + 1, 1.0f - f, f};
}

// Along y, the rows are clamped but their weights are kept.
ResizeTaps tapsAlongY(int d, int source, int destination) {
  const double scale = 1.0 / (static_cast<double>(destination) / source);
  float f = static_cast<float>((d + 0.5) * scale - 0.5);
  const int s = cvFloor(f);
  f -= static_cast<float>(s);
  return {std::clamp(s, 0, source - 1), std::clamp(s + 1, 0, source - 1), 1.0f - f, f};
}

// Channel `c` of a row of a CV_32FC2 field, resampled along x by `t`.
float resampledAlongX(const float* row, const ResizeTaps& t, int c) {
  if (t.second == t.first) return row[2 * t.first + c];
  return row[2 * t.first + c] * t.w_first + row[2 * t.second + c] * t.w_second;
}

// Channel `c` of a CV_32FC2 field resampled at one destination pixel.
float resampledAt(const cv::Mat& field, int c, const ResizeTaps& x, const ResizeTaps& y) {
  return resampledAlongX(field.ptr<float>(y.first), x, c) * y.w_first +
         resampledAlongX(field.ptr<float>(y.second), x, c) * y.w_second;
}

// cv::resize of a CV_32FC2 field to half its size exactly (INTER_LINEAR becomes its area
// averaging there), at one destination pixel.
float halvedAt(const cv::Mat& field, int c, int x, int y) {
  const float* top = field.ptr<float>(2 * y) + 4 * x + c;
  const float* bottom = field.ptr<float>(2 * y + 1) + 4 * x + c;
  return ((top[0] + top[2]) + (bottom[0] + bottom[2])) * 0.25f;
}

// A row of a CV_32FC2 field `source` pixels wide resampled along x to `out` (taps.size() pixels).
void resampleRow(const float* row, int source, const std::vector<ResizeTaps>& taps, float* out) {
  const int width = static_cast<int>(taps.size());
  const auto one_by_one = [&](int x) {
    for (int c = 0; c < 2; ++c) out[2 * x + c] = resampledAlongX(row, taps[x], c);
  };
  if (width != 2 * source || source < 3) {
    for (int x = 0; x < width; ++x) one_by_one(x);
    return;
  }
  // Twice the size: pixel 2k is a quarter of k - 1 and three of k, 2k + 1 three quarters of k and
  // one of k + 1 (the taps' weights, exactly), two pixels (four floats) at a time.
  const v_float32x4 near(0.25f, 0.25f, 0.75f, 0.75f), far(0.75f, 0.75f, 0.25f, 0.25f);
  for (int k = 1; k + 1 < source; ++k) {
    const v_float32x4 left = cv::v_load(row + 2 * (k - 1));  // pixels k - 1 and k
    const v_float32x4 right = cv::v_load(row + 2 * k);       // pixels k and k + 1
    cv::v_store(out + 4 * k, left * near + cv::v_combine_high(left, right) * far);
  }
  for (const int x : {0, 1, width - 2, width - 1}) one_by_one(x);
}

// ---- the structure tensor of every patch --------------------------------------------------------

// Per row of the gradients, the sums over each patch's eight columns of gx², gy², gx·gy, gx, gy:
// exact (integers under 2^24 in float), as OpenCV's running sums along a row are.
void sumAlongRows(const cv::Mat& grad_x, const cv::Mat& grad_y, int patches_across,
                  std::vector<float>* blocks, std::vector<float>* sums) {
  const int blocks_across = patches_across + 1;  // four columns each; a patch spans two
  blocks->resize(5 * static_cast<size_t>(blocks_across));
  sums->resize(5 * static_cast<size_t>(patches_across) * grad_x.rows);
  float* xx = blocks->data();
  float* yy = xx + blocks_across;
  float* xy = yy + blocks_across;
  float* x = xy + blocks_across;
  float* y = x + blocks_across;
  for (int r = 0; r < grad_x.rows; ++r) {
    const float* gx = grad_x.ptr<float>(r);
    const float* gy = grad_y.ptr<float>(r);
    int b = 0;
    for (; b + 4 <= blocks_across; b += 4) {
      v_float32x4 x0, x1, x2, x3, y0, y1, y2, y3;
      cv::v_load_deinterleave(gx + 4 * b, x0, x1, x2, x3);
      cv::v_load_deinterleave(gy + 4 * b, y0, y1, y2, y3);
      cv::v_store(xx + b, x0 * x0 + x1 * x1 + x2 * x2 + x3 * x3);
      cv::v_store(yy + b, y0 * y0 + y1 * y1 + y2 * y2 + y3 * y3);
      cv::v_store(xy + b, x0 * y0 + x1 * y1 + x2 * y2 + x3 * y3);
      cv::v_store(x + b, x0 + x1 + x2 + x3);
      cv::v_store(y + b, y0 + y1 + y2 + y3);
    }
    for (; b < blocks_across; ++b) {
      xx[b] = yy[b] = xy[b] = x[b] = y[b] = 0;
      for (int c = 4 * b; c < 4 * b + 4; ++c) {
        xx[b] += gx[c] * gx[c];
        yy[b] += gy[c] * gy[c];
        xy[b] += gx[c] * gy[c];
        x[b] += gx[c];
        y[b] += gy[c];
      }
    }
    for (int q = 0; q < 5; ++q) {
      const float* block = blocks->data() + q * blocks_across;
      float* sum = sums->data() + (static_cast<size_t>(q) * grad_x.rows + r) * patches_across;
      for (int p = 0; p < patches_across; ++p) sum[p] = block[p] + block[p + 1];
    }
  }
}

// Down the columns, as OpenCV sums them: eight rows added in turn, then a running sum that adds
// a row and takes one away, read every kPatchStride rows — in float, rounding where it does.
void sumDownColumns(const std::vector<float>& row_sums, int rows, int patches_across,
                    int patches_down, std::vector<float>* totals, std::vector<float>* running) {
  totals->resize(5 * static_cast<size_t>(patches_across) * patches_down);
  running->resize(patches_across);
  for (int q = 0; q < 5; ++q) {
    const float* sums = row_sums.data() + static_cast<size_t>(q) * rows * patches_across;
    float* total = totals->data() + static_cast<size_t>(q) * patches_down * patches_across;
    float* sum = running->data();
    std::fill(sum, sum + patches_across, 0.0f);
    for (int r = 0; r < kPatch; ++r) {
      for (int p = 0; p < patches_across; ++p) sum[p] += sums[r * patches_across + p];
    }
    std::copy(sum, sum + patches_across, total);
    for (int r = kPatch, down = 1; down < patches_down; ++r) {
      const float* entering = sums + r * patches_across;
      const float* leaving = sums + (r - kPatch) * patches_across;
      for (int p = 0; p < patches_across; ++p) sum[p] += entering[p] - leaving[p];
      if ((r - kPatch + 1) % kPatchStride == 0) {
        std::copy(sum, sum + patches_across, total + down++ * patches_across);
      }
    }
  }
}

// ---- one patch against the second image ------------------------------------------------------

// Where a flow vector takes a patch in the second image (bordered coordinates, clamped so that
// the patch stays within the border): the top-left of the 9x9 pixels its bilinear interpolation
// reads and the weights of the four neighbours (OpenCV's INIT_BILINEAR_WEIGHTS).
struct Landing {
  const float* window;
  float w00, w01, w10, w11;  // top-left, top-right, bottom-left, bottom-right
};

// One level's images as the patch search reads them.
struct SearchImages {
  const float* first;  // the first image's pixels
  int first_stride;
  const float* grad_x;
  const float* grad_y;
  int grad_stride;
  const float* second;  // the second image's top-left, border included
  int second_stride;
  float lowest, right, bottom;  // the clamps of a landing's top-left, bordered coordinates

  Landing landing(int i, int j, float ux, float uy) const {
    // Clamped with the bound first, so that a NaN flow lands on a bound rather than anywhere.
    const float y = std::min(bottom, std::max(lowest, i + uy + kBorder));
    const float x = std::min(right, std::max(lowest, j + ux + kBorder));
    // Both are positive, where truncation is floor (which SSE2 has no instruction for).
    const int row = static_cast<int>(y), col = static_cast<int>(x);
    const float fy = static_cast<float>(row), fx = static_cast<float>(col);
    return {second + row * second_stride + col, (fy + 1 - y) * (fx + 1 - x),
            (fy + 1 - y) * (x - fx), (y - fy) * (fx + 1 - x), (y - fy) * (x - fx)};
  }
};

// A patch's differences from its landing (the interpolated second image minus the first), row
// by row, the left four pixels then the right four.
struct PatchDiffs {
  v_float32x4 rows[2 * kPatch];
};

// How a patch matches at a landing: the mean-normalised SSD and, for a descent, the patch's
// gradients weighted by the differences (the Gauss-Newton step before the inverse tensor). The
// sums run over the lanes of two vectors per row and are reduced as OpenCV's
// processPatchMeanNorm and computeSSDMeanNorm do, so that the results are theirs to the bit.
struct PatchMatch {
  float ssd;
  float sum;  // of the differences
  float step_x, step_y;
};

// A step's component: the gradient weighted by the differences, less the share of their mean
// (the mean normalisation).
float stepComponent(const v_float32x4& weighted, float diff_sum, float grad_sum) {
  return cv::v_reduce_sum(weighted) - diff_sum * grad_sum / kPatchArea;
}

// The step of a match whose differences are known (`grad_x_sum`, `grad_y_sum`: the patch's
// gradients summed).
void stepFromDiffs(const SearchImages& images, int i, int j, const PatchDiffs& diffs,
                   float grad_x_sum, float grad_y_sum, PatchMatch* match) {
  const float* gx = images.grad_x + i * images.grad_stride + j;
  const float* gy = images.grad_y + i * images.grad_stride + j;
  v_float32x4 sum_gx = cv::v_setzero_f32(), sum_gy = sum_gx;
  for (int row = 0; row < kPatch; ++row) {
    const v_float32x4& left = diffs.rows[2 * row];
    const v_float32x4& right = diffs.rows[2 * row + 1];
    sum_gx += left * cv::v_load(gx) + right * cv::v_load(gx + 4);
    sum_gy += left * cv::v_load(gy) + right * cv::v_load(gy + 4);
    gx += images.grad_stride;
    gy += images.grad_stride;
  }
  match->step_x = stepComponent(sum_gx, match->sum, grad_x_sum);
  match->step_y = stepComponent(sum_gy, match->sum, grad_y_sum);
}

// A candidate's match (kStep false), its differences kept in *diffs for stepFromDiffs; or a
// descent's (kStep true), with its step, `diffs` unused.
template <bool kStep>
PatchMatch matchPatch(const SearchImages& images, int i, int j, const Landing& at,
                      PatchDiffs* diffs, float grad_x_sum = 0, float grad_y_sum = 0) {
  const v_float32x4 w00 = cv::v_setall_f32(at.w00), w01 = cv::v_setall_f32(at.w01);
  const v_float32x4 w10 = cv::v_setall_f32(at.w10), w11 = cv::v_setall_f32(at.w11);
  const float* first = images.first + i * images.first_stride + j;
  const float* gx = images.grad_x + i * images.grad_stride + j;
  const float* gy = images.grad_y + i * images.grad_stride + j;
  const float* second = at.window;
  v_float32x4 top_left = cv::v_load(second), top_right = cv::v_load(second + 4);
  v_float32x4 top_left1 = cv::v_load(second + 1), top_right1 = cv::v_load(second + 5);
  v_float32x4 sum = cv::v_setzero_f32(), sum_sq = sum, sum_gx = sum, sum_gy = sum;
  // Unrolled, the eight rows cost 4 % fewer instructions in the search (GCC keeps the loop).
#pragma GCC unroll 8
  for (int row = 0; row < kPatch; ++row) {
    second += images.second_stride;
    const v_float32x4 left = cv::v_load(second), right = cv::v_load(second + 4);
    const v_float32x4 left1 = cv::v_load(second + 1), right1 = cv::v_load(second + 5);
    const v_float32x4 diff_left =
        w00 * top_left + w01 * top_left1 + w10 * left + w11 * left1 - cv::v_load(first);
    const v_float32x4 diff_right =
        w00 * top_right + w01 * top_right1 + w10 * right + w11 * right1 - cv::v_load(first + 4);
    if constexpr (kStep) {
      sum_gx += diff_left * cv::v_load(gx) + diff_right * cv::v_load(gx + 4);
      sum_gy += diff_left * cv::v_load(gy) + diff_right * cv::v_load(gy + 4);
      gx += images.grad_stride;
      gy += images.grad_stride;
    } else {
      diffs->rows[2 * row] = diff_left;
      diffs->rows[2 * row + 1] = diff_right;
    }
    sum_sq += diff_left * diff_left + diff_right * diff_right;
    sum += diff_left + diff_right;
    top_left = left, top_right = right, top_left1 = left1, top_right1 = right1;
    first += images.first_stride;
  }
  const float total = cv::v_reduce_sum(sum);
  PatchMatch match{cv::v_reduce_sum(sum_sq) - total * total / kPatchArea, total, 0, 0};
  if constexpr (kStep) {
    match.step_x = stepComponent(sum_gx, total, grad_x_sum);
    match.step_y = stepComponent(sum_gy, total, grad_y_sum);
  }
  return match;
}

// ---- one visit of a patch ------------------------------------------------------------------

struct Flow {
  float x, y;
  bool operator==(const Flow& o) const { return x == o.x && y == o.y; }
};

// The best of a patch's candidates for its flow: its own first, then the others in turn, each
// taking the place only with a smaller SSD, as OpenCV tries them. The best's differences are
// kept (`diffs`: room for two).
class BestCandidate {
 public:
  BestCandidate(const SearchImages& images, int i, int j, Flow own, PatchDiffs* diffs)
      : images_(images), i_(i), j_(j), best_diffs_(&diffs[0]), spare_diffs_(&diffs[1]),
        flow_(own),
        match_(matchPatch<false>(images, i, j, images.landing(i, j, own.x, own.y), best_diffs_)) {}

  // The candidate's SSD, or NaN when it was not computed (the best's flow: the same SSD, which
  // would not win).
  float consider(Flow candidate) {
    if (candidate == flow_) return std::numeric_limits<float>::quiet_NaN();
    const PatchMatch m = matchPatch<false>(
        images_, i_, j_, images_.landing(i_, j_, candidate.x, candidate.y), spare_diffs_);
    if (m.ssd < match_.ssd) {
      flow_ = candidate, match_ = m;
      std::swap(best_diffs_, spare_diffs_);
    }
    return m.ssd;
  }

  // The same for a candidate whose SSD is known (NaN: not known), matched again only to win.
  void consider(Flow candidate, float ssd) {
    if (std::isnan(ssd) || ssd < match_.ssd) consider(candidate);
  }

  Flow flow() const { return flow_; }
  const PatchMatch& match() const { return match_; }
  const PatchDiffs& diffs() const { return *best_diffs_; }

 private:
  const SearchImages& images_;
  const int i_, j_;
  PatchDiffs* best_diffs_;
  PatchDiffs* spare_diffs_;
  Flow flow_;
  PatchMatch match_;
};

// Gauss-Newton steps from `start` (its match and differences known) until the SSD stops falling;
// the step that found it so is kept, as OpenCV keeps it. A descent that went further than a
// patch from its start is not trusted: the start is kept. The result goes to *x, *y.
void descend(const SearchImages& images, int i, int j, const DisFrame::PatchGradients& g,
             Flow start, PatchMatch m, const PatchDiffs& start_diffs, float* x, float* y) {
  stepFromDiffs(images, i, j, start_diffs, g.sum_x, g.sum_y, &m);
  float ux = start.x, uy = start.y, previous = kInf;
  for (int step = 1;; ++step) {
    ux -= g.inv_xx * m.step_x + g.inv_xy * m.step_y;
    uy -= g.inv_xy * m.step_x + g.inv_yy * m.step_y;
    if (m.ssd >= previous || step == kDescentSteps) break;
    previous = m.ssd;
    m = matchPatch<true>(images, i, j, images.landing(i, j, ux, uy), nullptr, g.sum_x, g.sum_y);
  }
  const float moved_x = ux - start.x, moved_y = uy - start.y;
  const double moved = std::sqrt(static_cast<double>(moved_x) * moved_x +
                                 static_cast<double>(moved_y) * moved_y);
  if (moved <= kPatch) {
    *x = ux, *y = uy;
  } else {
    *x = start.x, *y = start.y;
  }
}

// ---- densification ---------------------------------------------------------------------------

// The range of patches (rows or columns of them) that cover pixel index `p`, as OpenCV's
// densification counts them: the last pixels past the last patch belong to it.
struct Cover {
  int first, last;
};

Cover coverOf(int p, int patches) {
  const int last = std::min(p / kPatchStride, patches - 1);
  return {std::min(std::max(p / kPatchStride - 1, 0), last), last};
}

// The second image's bilinear value at four pixels of a row, moved by one flow vector: OpenCV's
// densification arithmetic lane by lane. `x0` holds the columns' integer parts; when they are
// consecutive (no lane clamped at a border) the pixels are loaded four at a time.
v_float32x4 bilinearRow(const float* top, const float* bottom, const v_int32x4& x0,
                        const v_float32x4& wx0, const v_float32x4& wx1, float w_top,
                        float w_bottom) {
  v_float32x4 top_left, top_right, bottom_left, bottom_right;
  const int start = x0.get0();
  const v_int32x4 consecutive = cv::v_setall_s32(start) + v_int32x4(0, 1, 2, 3);
  if (cv::v_check_all(x0 == consecutive)) {
    top_left = cv::v_load(top + start), top_right = cv::v_load(top + start + 1);
    bottom_left = cv::v_load(bottom + start), bottom_right = cv::v_load(bottom + start + 1);
  } else {
    int x[4];
    cv::v_store(x, x0);
    top_left = v_float32x4(top[x[0]], top[x[1]], top[x[2]], top[x[3]]);
    top_right = v_float32x4(top[x[0] + 1], top[x[1] + 1], top[x[2] + 1], top[x[3] + 1]);
    bottom_left = v_float32x4(bottom[x[0]], bottom[x[1]], bottom[x[2]], bottom[x[3]]);
    bottom_right =
        v_float32x4(bottom[x[0] + 1], bottom[x[1] + 1], bottom[x[2] + 1], bottom[x[3] + 1]);
  }
  const v_float32x4 wt = cv::v_setall_f32(w_top), wb = cv::v_setall_f32(w_bottom);
  return wx1 * wb * bottom_right + wx0 * wb * bottom_left + wx1 * wt * top_right +
         wx0 * wt * top_left;
}

}  // namespace

const float* DisFrame::Level::pixels() const { return image.ptr<float>(kBorder) + kBorder; }

// A level's size and its grid of patches.
struct DisFlow::LevelShape {
  int w, h;    // pixels
  int ws, hs;  // patches

  explicit LevelShape(cv::Size size)
      : w(size.width),
        h(size.height),
        ws(1 + (size.width - kPatch) / kPatchStride),
        hs(1 + (size.height - kPatch) / kPatchStride) {}
};

DisFlow::DisFlow(int finest_scale) : finest_scale_(finest_scale) { CV_Assert(finest_scale >= 0); }

int DisFlow::reach() const { return kPatch << finest_scale_; }

void DisFlow::prepare(const cv::Mat& grey, DisFrame* frame) {
  CV_Assert(grey.type() == CV_8UC1 && grey.isContinuous());
  CV_Assert(std::min(grey.cols, grey.rows) >= 2 * kPatch);
  const auto [finest, coarsest] = searchedScales(grey.size(), finest_scale_);
  frame->size_ = grey.size();
  frame->finest_scale_ = finest;
  frame->levels_.resize(coarsest - finest + 1);
  cv::Mat above = grey;  // the finer level, CV_8U
  for (size_t l = 0; l < frame->levels_.size(); ++l) {
    DisFrame::Level& level = frame->levels_[l];
    level.size = l == 0 ? cv::Size(grey.cols >> finest, grey.rows >> finest)
                        : cv::Size(above.cols / 2, above.rows / 2);
    if (level.size != above.size()) {
      cv::resize(above, level.grey, level.size, 0, 0, cv::INTER_AREA);
      above = level.grey;
    }
    prepareLevel(above, &level);
  }
}

// A level's image as floats with its border, its gradients and its patches' tensors, as OpenCV's
// DIS computes them (copyMakeBorder, spatialGradient, precomputeStructureTensor).
void DisFlow::prepareLevel(const cv::Mat& grey, DisFrame::Level* level) {
  cv::copyMakeBorder(grey, level->grey_bordered, kBorder, kBorder, kBorder, kBorder,
                     cv::BORDER_REPLICATE);
  level->grey_bordered.convertTo(level->image, CV_32F);
  cv::spatialGradient(grey, level->grad_x16, level->grad_y16);
  level->grad_x16.convertTo(level->grad_x, CV_32F);
  level->grad_y16.convertTo(level->grad_y, CV_32F);
  const LevelShape shape(level->size);
  sumAlongRows(level->grad_x, level->grad_y, shape.ws, &blocks_, &row_sums_);
  sumDownColumns(row_sums_, shape.h, shape.ws, shape.hs, &totals_, &running_);
  const size_t patches = static_cast<size_t>(shape.ws) * shape.hs;
  const float* xx = totals_.data();
  const float* yy = xx + patches;
  const float* xy = yy + patches;
  const float* x = xy + patches;
  const float* y = x + patches;
  level->patches.resize(patches);
  for (size_t k = 0; k < patches; ++k) {
    float det = xx[k] * yy[k] - xy[k] * xy[k];
    if (std::abs(det) < kEps) det = kEps;  // a flat patch: OpenCV's least determinant
    level->patches[k] = {yy[k] / det, -xy[k] / det, xx[k] / det, x[k], y[k]};
  }
}

void DisFlow::calc(const DisFrame& from, const DisFrame& to, const cv::Mat& initial,
                   cv::Mat* flow) {
  CV_Assert(!from.empty() && from.size() == to.size() &&
            from.finest_scale_ == to.finest_scale_ && from.levels_.size() == to.levels_.size());
  const bool warm = !initial.empty();
  CV_Assert(!warm || (initial.type() == CV_32FC2 && initial.size() == from.size()));
  const int finest = from.finest_scale_;
  const LevelShape finest_shape(from.levels_[0].size);
  const size_t most_patches = static_cast<size_t>(finest_shape.ws) * finest_shape.hs;
  for (auto* buffer :
       {&sparse_x_, &sparse_y_, &start_x_, &start_y_, &initial_x_, &initial_y_, &initial_ssd_}) {
    buffer->resize(most_patches);
  }
  dense_.create(finest_shape.h, finest_shape.w, CV_32FC2);
  // The initial flow is read at every level before *flow, which it may be, is written.
  for (int l = static_cast<int>(from.levels_.size()) - 1; l >= 0; --l) {
    const DisFrame::Level& first = from.levels_[l];
    const LevelShape shape(first.size);
    if (l == static_cast<int>(from.levels_.size()) - 1) {
      std::fill_n(start_x_.begin(), static_cast<size_t>(shape.ws) * shape.hs, 0.0f);
      std::fill_n(start_y_.begin(), static_cast<size_t>(shape.ws) * shape.hs, 0.0f);
    } else {
      sampleCoarserFlow(shape);
    }
    if (warm) sampleInitialFlow(initial, shape, finest + l);
    searchPatches(first, to.levels_[l], shape, warm);
    dense_level_ = cv::Mat(shape.h, shape.w, CV_32FC2, dense_.data);
    densify(first, to.levels_[l], shape, l == 0 ? static_cast<float>(1 << finest) : 1.0f,
            &dense_level_);
  }
  if (finest == 0) {
    dense_level_.copyTo(*flow);
  } else {
    flow->create(from.size(), CV_32FC2);
    upsample(dense_level_, flow);
  }
}

// cv::resize(dense, flow, flow's size, INTER_LINEAR) with its arithmetic: each source row
// resampled along x once, then pairs of them blended. OpenCV's resize does the same, with a
// scalar pass along x; here twice the size, the common case, goes four floats at a time.
void DisFlow::upsample(const cv::Mat& dense, cv::Mat* flow) {
  const int width = flow->cols, floats = 2 * flow->cols;
  x_taps_.resize(width);
  for (int x = 0; x < width; ++x) x_taps_[x] = tapsAlongX(x, dense.cols, width);
  int held[2] = {-1, -1};  // the source row each of resampled_rows_ holds
  const auto resampled = [&](int source, int keep) {
    for (int slot = 0; slot < 2; ++slot) {
      if (held[slot] == source) return resampled_rows_[slot].data();
    }
    const int slot = held[0] == keep ? 1 : 0;
    resampled_rows_[slot].resize(floats);
    resampleRow(dense.ptr<float>(source), dense.cols, x_taps_, resampled_rows_[slot].data());
    held[slot] = source;
    return resampled_rows_[slot].data();
  };
  for (int y = 0; y < flow->rows; ++y) {
    const ResizeTaps t = tapsAlongY(y, dense.rows, flow->rows);
    const float* top = resampled(t.first, t.second);
    const float* bottom = resampled(t.second, t.first);
    float* out = flow->ptr<float>(y);
    const v_float32x4 w_top = cv::v_setall_f32(t.w_first), w_bottom = cv::v_setall_f32(t.w_second);
    int x = 0;
    for (; x + 4 <= floats; x += 4) {
      cv::v_store(out + x, cv::v_load(top + x) * w_top + cv::v_load(bottom + x) * w_bottom);
    }
    for (; x < floats; ++x) out[x] = top[x] * t.w_first + bottom[x] * t.w_second;
  }
}

// The coarser level's dense flow (dense_level_), scaled up to this level as cv::resize and a
// doubling would make it, at each patch's centre: where the search at this level starts.
void DisFlow::sampleCoarserFlow(const LevelShape& shape) {
  const cv::Mat& coarser = dense_level_;
  for (int is = 0; is < shape.hs; ++is) {
    const ResizeTaps y = tapsAlongY(is * kPatchStride + kPatch / 2, coarser.rows, shape.h);
    for (int js = 0; js < shape.ws; ++js) {
      const ResizeTaps x = tapsAlongX(js * kPatchStride + kPatch / 2, coarser.cols, shape.w);
      const size_t k = static_cast<size_t>(is) * shape.ws + js;
      start_x_[k] = resampledAt(coarser, 0, x, y) * 2.0f;
      start_y_[k] = resampledAt(coarser, 1, x, y) * 2.0f;
    }
  }
}

// The initial flow (full size) scaled to this level as OpenCV's DIS scales it (cv::resize, then
// divided by the level's factor), at each patch's centre.
void DisFlow::sampleInitialFlow(const cv::Mat& initial, const LevelShape& shape, int scale) {
  const float factor = 1.0f / static_cast<float>(1 << scale);
  const bool same = initial.cols == shape.w && initial.rows == shape.h;
  const bool halved = initial.cols == 2 * shape.w && initial.rows == 2 * shape.h;
  for (int is = 0; is < shape.hs; ++is) {
    const int yc = is * kPatchStride + kPatch / 2;
    const ResizeTaps y = tapsAlongY(yc, initial.rows, shape.h);
    for (int js = 0; js < shape.ws; ++js) {
      const int xc = js * kPatchStride + kPatch / 2;
      const size_t k = static_cast<size_t>(is) * shape.ws + js;
      float fx, fy;
      if (same) {
        const cv::Vec2f& v = initial.at<cv::Vec2f>(yc, xc);
        fx = v[0], fy = v[1];
      } else if (halved) {
        fx = halvedAt(initial, 0, xc, yc), fy = halvedAt(initial, 1, xc, yc);
      } else {
        const ResizeTaps x = tapsAlongX(xc, initial.cols, shape.w);
        fx = resampledAt(initial, 0, x, y), fy = resampledAt(initial, 1, x, y);
      }
      initial_x_[k] = fx * factor;
      initial_y_[k] = fy * factor;
    }
  }
}

// OpenCV's patch inverse search with spatial propagation: in each band of patch rows, a forward
// pass (top-left to bottom-right) and a backward pass. A patch takes the best of its flow, the
// initial flow's and its already visited neighbours', then descends from there.
void DisFlow::searchPatches(const DisFrame::Level& from, const DisFrame::Level& to,
                            const LevelShape& shape, bool warm) {
  const SearchImages images{from.pixels(),
                            static_cast<int>(from.image.step1()),
                            from.grad_x.ptr<float>(),
                            from.grad_y.ptr<float>(),
                            static_cast<int>(from.grad_x.step1()),
                            to.image.ptr<float>(),
                            static_cast<int>(to.image.step1()),
                            static_cast<float>(kBorder - kPatch + 1),
                            static_cast<float>(kBorder + shape.w - 1),
                            static_cast<float>(kBorder + shape.h - 1)};
  float* sx = sparse_x_.data();
  float* sy = sparse_y_.data();
  // The candidates' differences are kept: the descent's first step, at the best candidate, is
  // taken from there (OpenCV computes them again).
  PatchDiffs diffs[2];
  const int band_rows = static_cast<int>(std::ceil(shape.hs / static_cast<double>(kStripes)));
  for (int band = 0; band < kStripes; ++band) {
    const int band_start = std::min(band * band_rows, shape.hs);
    const int band_end = std::min((band + 1) * band_rows, shape.hs);
    for (int pass = 0; pass < 2; ++pass) {
      const int dir = pass == 0 ? 1 : -1;
      const int first_row = pass == 0 ? band_start : band_end - 1;
      const int first_col = pass == 0 ? 0 : shape.ws - 1;
      for (int is = first_row; is >= band_start && is < band_end; is += dir) {
        for (int js = first_col; js >= 0 && js < shape.ws; js += dir) {
          const int k = is * shape.ws + js;
          const int i = is * kPatchStride, j = js * kPatchStride;
          if (pass == 0) sx[k] = start_x_[k], sy[k] = start_y_[k];
          BestCandidate best(images, i, j, {sx[k], sy[k]}, diffs);
          // The initial flow's candidate is tried in both passes at the same place: the second
          // pass takes its SSD from the first.
          if (warm && pass == 0) initial_ssd_[k] = best.consider({initial_x_[k], initial_y_[k]});
          if (warm && pass == 1) best.consider({initial_x_[k], initial_y_[k]}, initial_ssd_[k]);
          if (js != first_col) best.consider({sx[k - dir], sy[k - dir]});
          if (is != first_row) best.consider({sx[k - dir * shape.ws], sy[k - dir * shape.ws]});
          descend(images, i, j, from.patches[k], best.flow(), best.match(), best.diffs(), &sx[k],
                  &sy[k]);
        }
      }
    }
  }
}

// OpenCV's densification: each pixel's flow is the average of the flows of the patches that
// cover it, each weighted by 1 / max(1, |the pixel's difference under that flow|). Four pixels
// of a row share their patches; the arithmetic is OpenCV's lane by lane. `scale` multiplies the
// result (the finest level's factor to the frame's size, exact as a power of two).
void DisFlow::densify(const DisFrame::Level& from, const DisFrame::Level& to,
                      const LevelShape& shape, float scale, cv::Mat* dense) {
  const float right = shape.w - 1.0f - kEps, bottom = shape.h - 1.0f - kEps;
  const float* second = to.pixels();  // once: the library is built -fPIC, where it is not inlined
  const int second_stride = static_cast<int>(to.image.step1());
  const v_float32x4 zero = cv::v_setzero_f32(), one = cv::v_setall_f32(1.0f);
  const v_float32x4 lanes(0, 1, 2, 3);
  const v_float32x4 right_v = cv::v_setall_f32(right), scale_v = cv::v_setall_f32(scale);
  for (int i = 0; i < shape.h; ++i) {
    const Cover rows = coverOf(i, shape.hs);
    const float* first = from.pixels() + i * static_cast<int>(from.image.step1());
    float* out = dense->ptr<float>(i);
    for (int j = 0; j < shape.w; j += kPatchStride) {
      const Cover cols = coverOf(j, shape.ws);
      const v_float32x4 column = cv::v_setall_f32(static_cast<float>(j)) + lanes;
      const v_float32x4 pixel = cv::v_load(first + j);
      v_float32x4 sum_x = zero, sum_y = zero, sum_w = zero;
      for (int is = rows.first; is <= rows.last; ++is) {
        for (int js = cols.first; js <= cols.last; ++js) {
          const int k = is * shape.ws + js;
          const float y = std::min(bottom, std::max(0.0f, i + sparse_y_[k]));
          const int y0 = static_cast<int>(y);
          const float y0f = static_cast<float>(y0);
          const float w_bottom = y - y0f, w_top = (y0f + 1) - y;
          const v_float32x4 fx = cv::v_setall_f32(sparse_x_[k]);
          const v_float32x4 x = cv::v_min(cv::v_max(column + fx, zero), right_v);
          const v_int32x4 x0 = cv::v_trunc(x);
          const v_float32x4 x0f = cv::v_cvt_f32(x0);  // x0 + 1 is exact in float too
          const v_float32x4 wx1 = x - x0f, wx0 = (x0f + one) - x;
          const float* top = second + y0 * second_stride;
          const v_float32x4 diff =
              bilinearRow(top, top + second_stride, x0, wx0, wx1, w_top, w_bottom) - pixel;
          const v_float32x4 weight = one / cv::v_max(one, cv::v_abs(diff));
          sum_x += weight * fx;
          sum_y += weight * cv::v_setall_f32(sparse_y_[k]);
          sum_w += weight;
        }
      }
      v_float32x4 interleaved[2];
      cv::v_zip(sum_x / sum_w * scale_v, sum_y / sum_w * scale_v, interleaved[0], interleaved[1]);
      if (j + kPatchStride <= shape.w) {
        cv::v_store(out + 2 * j, interleaved[0]);
        cv::v_store(out + 2 * j + 4, interleaved[1]);
      } else {
        float values[8];
        cv::v_store(values, interleaved[0]);
        cv::v_store(values + 4, interleaved[1]);
        std::copy(values, values + 2 * (shape.w - j), out + 2 * j);
      }
    }
  }
}

cv::Ptr<cv::DISOpticalFlow> openCvDis(int finest_scale) {
  cv::Ptr<cv::DISOpticalFlow> dis = cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_FAST);
  dis->setFinestScale(finest_scale);
  dis->setVariationalRefinementIterations(0);
  return dis;
}

}  // namespace movseg
