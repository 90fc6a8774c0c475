#include "cut/evidence_cut.h"

#include <array>
#include <cmath>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "core/frame.h"
#include "cut/grid_energy.h"
#include "cut/grid_max_flow.h"

namespace movseg {
namespace {

// weight * exp(-beta d) of a squared colour step d between 8-bit colours, an integer. Looked up
// for the small steps, where most of an image's are (76 to 93 % of the edges of DAVIS frames at
// 320 pixels wide are below 2,048), so that std::exp runs once per value, not once per edge.
class ContrastWeight {
 public:
  ContrastWeight(float weight, float beta) : weight_(weight), beta_(beta) {
    for (int step = 0; step < kTabled; ++step) table_[step] = of(static_cast<float>(step));
  }

  float operator()(float step) const {
    return step < kTabled ? table_[static_cast<int>(step)] : of(step);
  }

 private:
  static constexpr int kTabled = 2048;

  float of(float step) const { return weight_ * std::exp(-beta_ * step); }

  float weight_, beta_;
  std::array<float, kTabled> table_;
};

// The costs of labelling a block of evidence e foreground, max(-e, 0), and background,
// max(e, 0): cv::max with a scalar allocates a copy of it on every call. A zero cost is +0 here
// where cv::max may keep a -0; the sign of a zero changes no sum or comparison of the cut.
void costs(const cv::Mat& evidence, cv::Mat* fg, cv::Mat* bg) {
  fg->create(evidence.size(), CV_32F);
  bg->create(evidence.size(), CV_32F);
  for (int y = 0; y < evidence.rows; ++y) {
    const float* e = evidence.ptr<float>(y);
    float* f = fg->ptr<float>(y);
    float* b = bg->ptr<float>(y);
    for (int x = 0; x < evidence.cols; ++x) {
      f[x] = e[x] < 0 ? -e[x] : 0.f;
      b[x] = e[x] > 0 ? e[x] : 0.f;
    }
  }
}

// The size of the 2x2 blocks of an image of `size` (a last odd row or column is a block).
cv::Size blocksOf(cv::Size size) { return scaledSize(size, (size.width + 1) / 2); }

// The sums of one channel's 16 pixels two by two, in 16-bit lanes.
cv::v_uint16x8 pairSums(const cv::v_uint8x16& channel) {
  const cv::v_uint16x8 pairs = cv::v_reinterpret_as_u16(channel);
  return (pairs & cv::v_setall_u16(0xff)) + (pairs >> 8);
}

// `bgr` at its blocks' size by area averaging, as cv::resize's INTER_AREA makes it: at exactly
// half the size, each block the rounded mean of its 2x2 pixels, which cv::resize computes after
// allocating a table of offsets; other sizes (an odd side) by cv::resize. Sixteen blocks at a
// time, the channels apart (a loop over bytes three apart would cost twice OpenCV's).
void toBlocks(const cv::Mat& bgr, cv::Mat* blocks) {
  const cv::Size size = blocksOf(bgr.size());
  if (size * 2 != bgr.size()) {
    cv::resize(bgr, *blocks, size, 0, 0, cv::INTER_AREA);
    return;
  }
  blocks->create(size, CV_8UC3);
  const cv::v_uint16x8 two = cv::v_setall_u16(2);
  for (int y = 0; y < size.height; ++y) {
    const uchar* top = bgr.ptr<uchar>(2 * y);
    const uchar* bottom = bgr.ptr<uchar>(2 * y + 1);
    uchar* out = blocks->ptr<uchar>(y);
    int x = 0;
    for (; x + 16 <= size.width; x += 16) {
      cv::v_uint16x8 means[2][3];  // blocks x to x + 7 and x + 8 to x + 15, by channel
      for (int half = 0; half < 2; ++half) {
        cv::v_uint8x16 upper[3], lower[3];
        cv::v_load_deinterleave(top + 6 * x + 48 * half, upper[0], upper[1], upper[2]);
        cv::v_load_deinterleave(bottom + 6 * x + 48 * half, lower[0], lower[1], lower[2]);
        for (int c = 0; c < 3; ++c) {
          means[half][c] = (pairSums(upper[c]) + pairSums(lower[c]) + two) >> 2;
        }
      }
      cv::v_store_interleave(out + 3 * x, cv::v_pack(means[0][0], means[1][0]),
                             cv::v_pack(means[0][1], means[1][1]),
                             cv::v_pack(means[0][2], means[1][2]));
    }
    for (; x < size.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int at = 6 * x + c;
        out[3 * x + c] =
            static_cast<uchar>((top[at] + top[at + 3] + bottom[at] + bottom[at + 3] + 2) >> 2);
      }
    }
  }
}

// The blocks' labels (0/255) at the pixels of `size`, as upscaledMask makes them: at exactly
// twice the blocks' size, each pixel's nearest block weighs 9/16 in its bilinear interpolation
// (3/4 at the borders) and the others 7/16 together, so that the threshold at half keeps the
// nearest block's label, the one it lies in: here without cv::resize's allocations. Other
// sizes (an odd side) by upscaledMask.
void blocksToPixels(const cv::Mat& labels, cv::Size size, cv::Mat* mask) {
  if (labels.size() * 2 != size) {
    upscaledMask(labels, size, mask);
    return;
  }
  mask->create(size, CV_8U);
  for (int y = 0; y < size.height; y += 2) {  // a row of blocks makes two equal pixel rows
    const uchar* block = labels.ptr<uchar>(y / 2);
    uchar* out = mask->ptr<uchar>(y);
    int b = 0;
    for (; b + 16 <= labels.cols; b += 16) {  // each byte twice: sixteen blocks at a time
      cv::v_uint8x16 left, right;
      const cv::v_uint8x16 blocks = cv::v_load(block + b);
      cv::v_zip(blocks, blocks, left, right);
      cv::v_store(out + 2 * b, left);
      cv::v_store(out + 2 * b + 16, right);
    }
    for (; b < labels.cols; ++b) out[2 * b] = out[2 * b + 1] = block[b];
    std::memcpy(mask->ptr<uchar>(y + 1), out, static_cast<size_t>(size.width));
  }
}

}  // namespace

void blockContrast(const cv::Mat& bgr, double smoothness, BlockContrast* contrast) {
  toBlocks(bgr, &contrast->block_bgr);
  cv::Mat& colour = contrast->colour;
  contrast->block_bgr.convertTo(colour, CV_32FC3);
  // Edge weights smoothness * exp(-beta |dC|^2) to the right and down (squaredColourSteps), in
  // the contrast's buffers (a first frame makes them).
  GridEnergy steps;
  steps.right = contrast->right;
  steps.down = contrast->down;
  const ContrastWeight weight(static_cast<float>(smoothness), squaredColourSteps(colour, &steps));
  const int w = colour.cols, h = colour.rows;
  for (int y = 0; y < h; ++y) {
    float* right = steps.right.ptr<float>(y);
    float* down = steps.down.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) right[x] = weight(right[x]);
      if (y + 1 < h) down[x] = weight(down[x]);
    }
  }
  contrast->right = steps.right;
  contrast->down = steps.down;
}

void EvidenceCut::cut(const cv::Mat& evidence, const BlockContrast& contrast, int* nodes,
                      cv::Mat* mask) {
  CV_Assert(contrast.right.size() == blocksOf(evidence.size()));
  cv::resize(evidence, block_evidence_, contrast.right.size(), 0, 0, cv::INTER_AREA);
  costs(block_evidence_, &cost_fg_, &cost_bg_);
  const GridEnergy energy{cost_fg_, cost_bg_, contrast.right, contrast.down};
  decidedPixels(energy, &decided_);
  max_flow_.label(energy, decided_, nodes, &labels_);
  blocksToPixels(labels_, evidence.size(), mask);
}

}  // namespace movseg
