// The bottom layer: input normalisation, working scales, and the prepared frame every stage reads.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

// Converts any supported frame to 8-bit BGR: grey and BGRA are converted, 16-bit is scaled by
// 1/256, float frames are read as [0, 1] (NaN as 0). Throws std::invalid_argument for an empty
// frame, an unsupported channel count, or a float frame with a value outside [0, 1]. The result
// may share the frame's data.
cv::Mat toBgr8(const cv::Mat& frame);

// toBgr8(frame) written into `bgr`, whose buffer is reused when it has the frame's size.
void toBgr8(const cv::Mat& frame, cv::Mat* bgr);

// Buffers for frames a pipeline keeps beyond the call that gave them: a buffer is handed out
// again once nothing but the pool refers to it, so a stream of frames of one size allocates
// nothing after its first few frames.
class FramePool {
 public:
  // A buffer of `size` and `type` that nobody else refers to.
  cv::Mat take(cv::Size size, int type);

 private:
  static constexpr size_t kMaxBuffers = 8;  // beyond, frames are allocated one by one
  std::vector<cv::Mat> buffers_;
};

// `image` resized to `size` (area interpolation); the same Mat when `size` is empty or equal.
cv::Mat resizedTo(const cv::Mat& image, cv::Size size);

// `image` scaled down to `size` into *out: halved by area averaging while it stays at least twice
// as large (OpenCV's fast integer path), then interpolated. Nearly INTER_AREA's anti-aliasing at
// a tenth of its cost for non-integer ratios (854 -> 320). `halved` is scratch.
void downscale(const cv::Mat& image, cv::Size size, cv::Mat* halved, cv::Mat* out);

// The size of `size` scaled to `width` (0 = unchanged), never upscaled, at least 1x1.
cv::Size scaledSize(cv::Size size, int width);

// A frame's working size for a working width (Params::alignment_width, segmentation_width;
// 0 = unchanged): scaledSize of the frame held landscape, so that its longer side is `width` —
// a portrait frame (a phone held upright) gets the pixels its landscape twin gets, not three
// times as many.
cv::Size workingSize(cv::Size size, int width);

// A frame at the working scales of Params, computed once and used by the pair (prev, cur) and
// the next pair.
struct PreparedFrame {
  cv::Mat bgr;                 // full resolution
  cv::Mat seg_bgr;             // segmentation scale (may share data with bgr)
  cv::Mat seg_smooth;          // seg_bgr blurred by Params::difference_blur, for eq. (4)
  cv::Mat small_grey;          // alignment scale
  double align_scale = 1.0;    // small_grey = bgr scaled by this
  double seg_scale = 1.0;      // seg_bgr = bgr scaled by this
};

PreparedFrame prepareFrame(const cv::Mat& bgr, const Params& params);

// A soft mask (CV_8U, above 127 moving) resized to `size` by bilinear interpolation into *out,
// not yet thresholded: what upscaledMask thresholds, and what EdgeSnap refines at the input's
// size. *out must not be `mask`.
void scaledMask(const cv::Mat& mask, cv::Size size, cv::Mat* out);

// *image (CV_8U or CV_32F) set to 0 where `where` (CV_8U, of its size) is non-zero: what
// Mat::setTo(0, where) does, without the copy of its scalar it allocates on every call.
void clearWhere(const cv::Mat& where, cv::Mat* image);

// scaledMask thresholded to 0/255 into *out, so that a mask computed at a working scale has
// smooth rather than blocky boundaries at full resolution; grey levels along its outline
// (EdgeSnap's) place it between pixels. *out must not be `mask`.
void upscaledMask(const cv::Mat& mask, cv::Size size, cv::Mat* out);

}  // namespace movseg
