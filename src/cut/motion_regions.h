// Motion the cut leaves out because it is small. The cut pays for a region's outline, so a mover
// too small for its evidence to pay for it stays out however clear its motion (README, Limits:
// about 26 px radius at the working width for a camouflaged one). Where nothing in the view can
// move for any other reason, a region of a pair's own motion evidence that lies apart from the
// mask, holds more of it than one flow patch can give, and did so on the last pair too, is a
// mover, whatever its outline costs. The last pair's say keeps out what changes once: a thing
// that vanishes leaves one pair's motion where it was.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// The regions of a stream's frames, in buffers kept from one frame to the next: at a fixed frame
// size neither call allocates after the first.
class MotionRegions {
 public:
  // Adds to *mask (CV_8U 0/255) every 8-connected region of positive `evidence` (CV_32F, the
  // mask's size) that touches no pixel of the mask, not even at a corner, whose evidence sums to
  // more than `least`, and that overlaps such a region of the last call. Returns how many were
  // added. A region that touches the mask is the cut's outline of a mover already found, and
  // stays as the cut decided it.
  int add(const cv::Mat& evidence, double least, cv::Mat* mask);

  // The next call's pair does not follow this one's (a pair between them was not seen still, or
  // the stream starts again): its regions are all first sightings. The buffers are made for
  // masks of `size` already, so that a view that stands still later allocates nothing then.
  void forget(cv::Size size);

  // The last call's regions over `least` (CV_8U): 255 where one joined the mask, 128 where one
  // was seen for the first time; zero after forget().
  void draw(cv::Mat* picture) const;

 private:
  void makeBuffers(cv::Size size);
  // Grows the region of `seed` into region_, marking it in seen_; whether it touches the mask.
  bool grow(const cv::Mat& evidence, const cv::Mat& mask, cv::Point seed);
  bool seenLastTime() const;  // whether region_ overlaps a region of the last call's

  cv::Mat seen_;  // CV_8U: pixels already in a region
  // CV_8U: this call's and the last call's regions over `least`: 2 where one joined the mask, 1
  // where first seen.
  cv::Mat regions_, last_;
  bool has_last_ = false;
  std::vector<cv::Point> region_, stack_;
};

}  // namespace movseg
