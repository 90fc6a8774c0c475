// Motion the cut leaves out because it is small. The cut pays for a region's outline, so a mover
// too small for its evidence to pay for it stays out however clear its motion (README, Limits:
// about 26 px radius at the working width for a camouflaged one). A region of a pair's own motion
// evidence that lies apart from the mask, holds more of it than one flow patch can give, did so
// on the last pair too, and whose unary (the pair's evidence with memory, colour and the prior)
// prefers foreground as a whole is such a mover: only its outline kept it out, and it joins the
// mask. What the cut keeps out for another reason stays out: a region that earlier pairs saw as
// background (a near post whose parallax no depth reading explains, water) has a negative sum,
// its memory and colour saying so, and a thing that vanishes leaves one pair's motion where it
// was, not two.
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
  // more than `least` and whose `unary` (CV_32F, the mask's size) sums to more than zero, and
  // that overlaps such a region of the last call. Returns how many were added. A region that
  // touches the mask is the cut's outline of a mover already found, and stays as the cut
  // decided it.
  int add(const cv::Mat& evidence, const cv::Mat& unary, double least, cv::Mat* mask);

  // The next call's pair does not follow this one's (no camera was fitted to a pair between
  // them, or the stream starts again): its regions are all first sightings. The buffers are made
  // for masks of `size` already, so that a later call allocates nothing.
  void forget(cv::Size size);

  // The last call's regions over `least` whose unary prefers foreground (CV_8U): 255 where one
  // joined the mask, 128 where one was seen for the first time; zero after forget().
  void draw(cv::Mat* picture) const;

 private:
  void makeBuffers(cv::Size size);
  // Marks every pixel of `evidence` and `mask` in the padded state_ image.
  void markPixels(const cv::Mat& evidence, const cv::Mat& mask);
  // Grows the region of the candidate at `seed` (an index into state_) into region_, marking
  // it seen; whether it touches the mask.
  bool grow(int seed);
  cv::Point pixelOf(int index) const;
  double sumOver(const cv::Mat& values) const;  // over region_
  bool seenLastTime() const;                    // whether region_ overlaps one of the last call's

  // CV_8U, the mask's size plus a border of one pixel that is never a candidate, so that a
  // pixel's eight neighbours are at fixed offsets without a bounds check.
  cv::Mat state_;
  // CV_8U: this call's and the last call's regions over `least` whose unary prefers foreground:
  // 2 where one joined the mask, 1 where first seen.
  cv::Mat regions_, last_;
  bool has_last_ = false;
  std::vector<int> region_, stack_;  // indices into state_
};

}  // namespace movseg
