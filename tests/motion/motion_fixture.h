// Frame pairs with a known camera model and a moving object, for the motion tests.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace movseg::test {

struct PairSpec {
  cv::Size size{320, 240};
  cv::Matx33d camera = cv::Matx33d::eye();  // previous -> current, the truth
  double object_fraction = 0.0;             // share of the frame the object covers
  cv::Point2d object_motion{6.4, 3.3};      // object displacement in the image, pixels
  double noise_sigma = 2.0;
  std::uint64_t seed = 1;
};

struct FramePair {
  cv::Mat prev, cur;   // 8-bit BGR
  cv::Mat cur_mask;    // object in the current frame
};

FramePair makePair(const PairSpec& spec);

// The affine of a rotation by `degrees` and a scale about the image centre, then a shift.
cv::Matx33d similarityAboutCentre(cv::Size size, double degrees, double scale, cv::Point2d shift,
                                  double shear = 0.0);

}  // namespace movseg::test
