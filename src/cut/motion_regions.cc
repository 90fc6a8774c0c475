#include "cut/motion_regions.h"

#include <cstring>

namespace movseg {

int MotionRegions::add(const cv::Mat& evidence, double least, cv::Mat* mask) {
  CV_Assert(evidence.type() == CV_32F && mask->type() == CV_8U && evidence.size() == mask->size());
  if (last_.size() != evidence.size()) has_last_ = false;
  makeBuffers(evidence.size());
  // Zeroed by hand: cv::Mat::setTo allocates on every call.
  std::memset(seen_.data, 0, seen_.total());
  std::memset(regions_.data, 0, regions_.total());
  int added = 0;
  for (int y = 0; y < evidence.rows; ++y) {
    const float* value = evidence.ptr<float>(y);
    for (int x = 0; x < evidence.cols; ++x) {
      if (value[x] <= 0 || mask->at<uchar>(y, x) != 0 || seen_.at<uchar>(y, x) != 0) continue;
      if (grow(evidence, *mask, {x, y})) continue;
      double sum = 0;
      for (const cv::Point& p : region_) sum += evidence.at<float>(p);
      if (sum <= least) continue;
      const bool taken = seenLastTime();
      for (const cv::Point& p : region_) regions_.at<uchar>(p) = taken ? 2 : 1;
      if (!taken) continue;
      for (const cv::Point& p : region_) mask->at<uchar>(p) = 255;
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
  for (cv::Mat* image : {&seen_, &regions_, &last_}) image->create(size, CV_8U);
  // A region holds each pixel once, and so does the stack that grows it: room for the whole
  // frame once, so that no frame allocates for a region larger than the last ones.
  region_.reserve(static_cast<size_t>(size.area()));
  stack_.reserve(static_cast<size_t>(size.area()));
}

bool MotionRegions::grow(const cv::Mat& evidence, const cv::Mat& mask, cv::Point seed) {
  region_.clear();
  stack_.assign(1, seed);
  seen_.at<uchar>(seed) = 1;
  bool touches = false;
  while (!stack_.empty()) {
    const cv::Point p = stack_.back();
    stack_.pop_back();
    region_.push_back(p);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point q(p.x + dx, p.y + dy);
        if (q.x < 0 || q.y < 0 || q.x >= evidence.cols || q.y >= evidence.rows) continue;
        if (mask.at<uchar>(q) != 0) {
          touches = true;
        } else if (evidence.at<float>(q) > 0 && seen_.at<uchar>(q) == 0) {
          seen_.at<uchar>(q) = 1;
          stack_.push_back(q);
        }
      }
    }
  }
  return touches;
}

bool MotionRegions::seenLastTime() const {
  if (!has_last_) return false;
  for (const cv::Point& p : region_) {
    if (last_.at<uchar>(p) != 0) return true;
  }
  return false;
}

}  // namespace movseg
