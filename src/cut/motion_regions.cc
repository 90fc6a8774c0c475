#include "cut/motion_regions.h"

#include <cstring>

#include <opencv2/core/hal/intrin.hpp>

namespace movseg {
namespace {

// A pixel of the state image: neither, positive evidence apart from the mask not yet in a
// region, in a region already, the mask. (Names of their own: a unity build puts this file's
// anonymous namespace beside other files'.)
constexpr uchar kNotMoving = 0, kCandidatePixel = 1, kGrownPixel = 2, kMaskPixel = 3;

}  // namespace

int MotionRegions::add(const cv::Mat& evidence, const cv::Mat& unary, double least, cv::Mat* mask) {
  CV_Assert(evidence.type() == CV_32F && unary.type() == CV_32F && mask->type() == CV_8U &&
            evidence.size() == mask->size() && unary.size() == mask->size());
  if (last_.size() != evidence.size()) has_last_ = false;
  makeBuffers(evidence.size());
  markPixels(evidence, *mask);
  // Zeroed by hand: cv::Mat::setTo allocates on every call.
  std::memset(regions_.data, 0, regions_.total());
  int added = 0;
  const int width = state_.cols;
  for (int y = 1; y + 1 < state_.rows; ++y) {
    const uchar* row = state_.ptr<uchar>(y);
    const uchar* end = row + width;
    // memchr skips to the next candidate; growing a region marks its pixels seen.
    for (const uchar* at = row;
         (at = static_cast<const uchar*>(std::memchr(at, kCandidatePixel, end - at))) != nullptr;) {
      const int seed = y * width + static_cast<int>(at - row);
      if (grow(seed) || sumOver(evidence) <= least || sumOver(unary) <= 0) continue;
      const bool taken = seenLastTime();
      for (int i : region_) regions_.at<uchar>(pixelOf(i)) = taken ? 2 : 1;
      if (!taken) continue;
      for (int i : region_) mask->at<uchar>(pixelOf(i)) = 255;
      ++added;
    }
  }
  std::swap(regions_, last_);
  has_last_ = true;
  return added;
}

void MotionRegions::forget(cv::Size size) {
  has_last_ = false;
  makeBuffers(size);
}

void MotionRegions::draw(cv::Mat* picture) const {
  if (!has_last_) {
    *picture = cv::Mat::zeros(last_.size(), CV_8U);
    return;
  }
  last_.convertTo(*picture, CV_8U, 127.5);  // 1 -> 128, 2 -> 255
}

void MotionRegions::makeBuffers(cv::Size size) {
  for (cv::Mat* image : {&regions_, &last_}) image->create(size, CV_8U);
  if (state_.size() != size + cv::Size(2, 2)) {
    state_ = cv::Mat::zeros(size + cv::Size(2, 2), CV_8U);  // its border stays kNotMoving
  }
  // A region holds each pixel once, and so does the stack that grows it: room for the whole
  // frame once, so that no frame allocates for a region larger than the last ones.
  region_.reserve(static_cast<size_t>(size.area()));
  stack_.reserve(static_cast<size_t>(size.area()));
}

void MotionRegions::markPixels(const cv::Mat& evidence, const cv::Mat& mask) {
  const cv::v_uint8x16 candidate = cv::v_setall_u8(kCandidatePixel),
                       in_mask = cv::v_setall_u8(kMaskPixel);
  const cv::v_uint8x16 none = cv::v_setzero_u8();
  const cv::v_float32x4 zero = cv::v_setzero_f32();
  // Where the evidence is positive: four float compares packed into 16 bytes of 0 or 0xff.
  const auto positive = [&](const float* e) {
    const auto half = [&](const float* at) {
      return cv::v_pack(cv::v_reinterpret_as_s32(cv::v_load(at) > zero),
                        cv::v_reinterpret_as_s32(cv::v_load(at + 4) > zero));
    };
    return cv::v_reinterpret_as_u8(cv::v_pack(half(e), half(e + 8)));
  };
  for (int y = 0; y < evidence.rows; ++y) {
    const float* e = evidence.ptr<float>(y);
    const uchar* m = mask.ptr<uchar>(y);
    uchar* s = state_.ptr<uchar>(y + 1) + 1;
    int x = 0;
    for (; x + 16 <= evidence.cols; x += 16) {
      const cv::v_uint8x16 free = cv::v_select(positive(e + x), candidate, none);
      cv::v_store(s + x, cv::v_select(cv::v_load(m + x) == none, free, in_mask));
    }
    for (; x < evidence.cols; ++x)
      s[x] = m[x] != 0 ? kMaskPixel : (e[x] > 0 ? kCandidatePixel : kNotMoving);
  }
}

bool MotionRegions::grow(int seed) {
  const int w = state_.cols;
  const int neighbours[] = {-w - 1, -w, -w + 1, -1, 1, w - 1, w, w + 1};
  uchar* state = state_.data;
  region_.clear();
  stack_.assign(1, seed);
  state[seed] = kGrownPixel;
  bool touches = false;
  while (!stack_.empty()) {
    const int p = stack_.back();
    stack_.pop_back();
    region_.push_back(p);
    for (int offset : neighbours) {
      uchar& q = state[p + offset];
      touches |= q == kMaskPixel;
      if (q != kCandidatePixel) continue;
      q = kGrownPixel;
      stack_.push_back(p + offset);
    }
  }
  return touches;
}

cv::Point MotionRegions::pixelOf(int index) const {
  return {index % state_.cols - 1, index / state_.cols - 1};
}

double MotionRegions::sumOver(const cv::Mat& values) const {
  double sum = 0;
  for (int i : region_) sum += values.at<float>(pixelOf(i));
  return sum;
}

bool MotionRegions::seenLastTime() const {
  if (!has_last_) return false;
  for (int i : region_) {
    if (last_.at<uchar>(pixelOf(i)) != 0) return true;
  }
  return false;
}

}  // namespace movseg
