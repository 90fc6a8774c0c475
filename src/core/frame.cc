#include "core/frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// A float frame in 0-255 (what cv2 or numpy arithmetic on 8-bit frames gives) would saturate
// to white and give an empty mask without a word: refuse it, saying what is expected.
void requireUnitRange(const cv::Mat& real) {
  double low = 0, high = 0;
  cv::minMaxLoc(real.reshape(1), &low, &high);
  if (low < 0 || high > 1) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "float frame values must be in [0, 1], got [%g, %g] (for 0-255, pass 8-bit "
                  "pixels or divide by 255)",
                  low, high);
    throw std::invalid_argument(text);
  }
}

// 8-bit, any channel count: the depth conversion of toBgr8.
cv::Mat eightBit(const cv::Mat& frame) {
  cv::Mat eight;
  switch (frame.depth()) {
    case CV_8U: return frame;
    case CV_8S: frame.convertTo(eight, CV_8U, 1.0, 128.0); break;
    case CV_16U: frame.convertTo(eight, CV_8U, 1.0 / 256.0); break;
    case CV_16S: frame.convertTo(eight, CV_8U, 1.0 / 256.0, 128.0); break;
    case CV_32F:
    case CV_64F: {
      cv::Mat finite;
      frame.convertTo(finite, CV_32F);  // patchNaNs takes 32-bit floats only
      cv::patchNaNs(finite, 0.0);       // NaN would otherwise become an arbitrary byte
      requireUnitRange(finite);
      finite.convertTo(eight, CV_8U, 255.0);
      break;
    }
    default:
      throw std::invalid_argument("unsupported pixel depth");
  }
  return eight;
}

}  // namespace

void toBgr8(const cv::Mat& frame, cv::Mat* bgr) {
  if (frame.empty()) throw std::invalid_argument("empty frame");
  if (frame.channels() != 1 && frame.channels() != 3 && frame.channels() != 4) {
    throw std::invalid_argument("unsupported channel count " + std::to_string(frame.channels()) +
                                " (expected 1, 3 or 4)");
  }
  const cv::Mat eight = eightBit(frame);
  switch (eight.channels()) {
    case 1: cv::cvtColor(eight, *bgr, cv::COLOR_GRAY2BGR); break;
    case 3: eight.copyTo(*bgr); break;
    default: cv::cvtColor(eight, *bgr, cv::COLOR_BGRA2BGR); break;
  }
}

cv::Mat toBgr8(const cv::Mat& frame) {
  if (frame.type() == CV_8UC3) return frame;
  cv::Mat bgr;
  toBgr8(frame, &bgr);
  return bgr;
}

cv::Mat FramePool::take(cv::Size size, int type) {
  for (cv::Mat& buffer : buffers_) {
    // Read atomically: another thread may be dropping its reference right now.
    if (buffer.u != nullptr && CV_XADD(&buffer.u->refcount, 0) != 1) continue;
    buffer.create(size, type);
    return buffer;
  }
  cv::Mat buffer(size, type);
  if (buffers_.size() < kMaxBuffers) buffers_.push_back(buffer);
  return buffer;
}

cv::Mat resizedTo(const cv::Mat& image, cv::Size size) {
  if (size.empty() || image.size() == size) return image;
  cv::Mat out;
  cv::resize(image, out, size, 0, 0, cv::INTER_AREA);
  return out;
}

void downscale(const cv::Mat& image, cv::Size size, cv::Mat* halved, cv::Mat* out) {
  const cv::Mat* source = &image;
  while (source->cols >= 2 * size.width && source->rows >= 2 * size.height) {
    cv::resize(*source, *halved, cv::Size(source->cols / 2, source->rows / 2), 0, 0, cv::INTER_AREA);
    source = halved;
  }
  if (source->size() == size) {
    source->copyTo(*out);
  } else {
    cv::resize(*source, *out, size, 0, 0, cv::INTER_LINEAR);
  }
}

cv::Size scaledSize(cv::Size size, int width) {
  if (width <= 0 || width >= size.width) return size;
  const double scale = static_cast<double>(width) / size.width;
  return {width, std::max(1, static_cast<int>(std::lround(size.height * scale)))};
}

cv::Size workingSize(cv::Size size, int width) {
  if (size.height <= size.width) return scaledSize(size, width);
  const cv::Size turned = scaledSize({size.height, size.width}, width);
  return {turned.height, turned.width};
}

PreparedFrame prepareFrame(const cv::Mat& bgr, const Params& params) {
  PreparedFrame f;
  f.bgr = bgr;
  const cv::Size seg_size = workingSize(bgr.size(), params.segmentation_width);
  f.seg_bgr = resizedTo(bgr, seg_size);
  f.seg_scale = static_cast<double>(seg_size.width) / bgr.cols;
  f.seg_smooth = f.seg_bgr;
  if (params.difference_blur > 0) {
    cv::GaussianBlur(f.seg_bgr, f.seg_smooth, cv::Size(), params.difference_blur);
  }

  const cv::Size align_size = workingSize(bgr.size(), params.alignment_width);
  const cv::Mat& align_source = align_size == seg_size ? f.seg_bgr : bgr;
  cv::cvtColor(resizedTo(align_source, align_size), f.small_grey, cv::COLOR_BGR2GRAY);
  f.align_scale = static_cast<double>(align_size.width) / bgr.cols;
  return f;
}

void scaledMask(const cv::Mat& mask, cv::Size size, cv::Mat* out) {
  cv::resize(mask, *out, size, 0, 0, cv::INTER_LINEAR);
}

void clearWhere(const cv::Mat& where, cv::Mat* image) {
  CV_Assert(where.type() == CV_8U && where.size() == image->size());
  CV_Assert(image->type() == CV_8U || image->type() == CV_32F);
  for (int y = 0; y < image->rows; ++y) {
    const uchar* w = where.ptr<uchar>(y);
    if (image->type() == CV_8U) {
      uchar* p = image->ptr<uchar>(y);
      for (int x = 0; x < image->cols; ++x) p[x] = w[x] != 0 ? 0 : p[x];
    } else {
      float* p = image->ptr<float>(y);
      for (int x = 0; x < image->cols; ++x) p[x] = w[x] != 0 ? 0.f : p[x];
    }
  }
}

void upscaledMask(const cv::Mat& mask, cv::Size size, cv::Mat* out) {
  if (mask.size() == size) {
    cv::threshold(mask, *out, 127, 255, cv::THRESH_BINARY);
  } else {  // one image, thresholded in place
    scaledMask(mask, size, out);
    cv::threshold(*out, *out, 127, 255, cv::THRESH_BINARY);
  }
}

}  // namespace movseg
