// Regions of motion apart from the mask (cut/motion_regions.h), on planted evidence with known
// sums: which are taken, which are left.
#include "cut/motion_regions.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

// Background evidence of -1 everywhere but the given boxes, each at `value`.
cv::Mat evidenceWith(const std::vector<cv::Rect>& boxes, float value) {
  cv::Mat evidence(60, 80, CV_32F, cv::Scalar(-1));
  for (const cv::Rect& box : boxes) evidence(box).setTo(value);
  return evidence;
}

// A 10x10 box at 2 sums to 200: over a least of 150, under one of 250.
const cv::Rect kBox(10, 10, 10, 10);

TEST(MotionRegions, ARegionSeenOnTwoPairsOverTheLeastJoinsTheMask) {
  MotionRegions regions;
  const cv::Mat evidence = evidenceWith({kBox}, 2.0f);
  cv::Mat mask = cv::Mat::zeros(evidence.size(), CV_8U);
  cv::Mat picture;
  EXPECT_EQ(regions.add(evidence, evidence, 150, &mask), 0);  // a first sighting
  EXPECT_EQ(cv::countNonZero(mask), 0);
  regions.draw(&picture);  // grey where first seen
  EXPECT_EQ(cv::countNonZero(picture == 128), 100);
  EXPECT_EQ(cv::countNonZero(picture), 100);
  EXPECT_EQ(regions.add(evidence, evidence, 150, &mask), 1);
  EXPECT_EQ(cv::countNonZero(mask), 100);
  EXPECT_EQ(cv::countNonZero(mask(kBox)), 100);
  regions.draw(&picture);  // white where taken
  EXPECT_EQ(cv::countNonZero(picture(kBox) == 255), 100);
  EXPECT_EQ(cv::countNonZero(picture), 100);
  regions.forget(evidence.size());
  regions.draw(&picture);
  EXPECT_EQ(cv::countNonZero(picture), 0);
}

TEST(MotionRegions, ARegionUnderTheLeastStaysOut) {
  MotionRegions regions;
  const cv::Mat evidence = evidenceWith({kBox}, 2.0f);
  cv::Mat mask = cv::Mat::zeros(evidence.size(), CV_8U);
  regions.add(evidence, evidence, 250, &mask);
  EXPECT_EQ(regions.add(evidence, evidence, 250, &mask), 0);
  EXPECT_EQ(cv::countNonZero(mask), 0);
}

// The last pair's region must overlap this one's: a mover moved by a few pixels does, a change
// in another place (a thing that vanished) does not.
TEST(MotionRegions, OnlyARegionOverlappingOneOfTheLastPairIsTaken) {
  MotionRegions regions;
  cv::Mat mask = cv::Mat::zeros(60, 80, CV_8U);
  const cv::Mat first = evidenceWith({kBox}, 2.0f);
  regions.add(first, first, 150, &mask);
  const cv::Mat moved = evidenceWith({kBox + cv::Point(3, 2)}, 2.0f);
  EXPECT_EQ(regions.add(moved, moved, 150, &mask), 1);
  EXPECT_EQ(cv::countNonZero(mask(kBox + cv::Point(3, 2))), 100);
  mask.setTo(0);
  const cv::Mat elsewhere = evidenceWith({cv::Rect(50, 30, 10, 10)}, 2.0f);
  EXPECT_EQ(regions.add(elsewhere, elsewhere, 150, &mask), 0);
  EXPECT_EQ(cv::countNonZero(mask), 0);
}

// What memory and colour keep out stays out: a region whose unary sums to zero or less (here
// -0.5 a pixel over the box: the pair's +2 outweighed) is not taken, however much evidence the
// pair alone gives it; +0.5 a pixel is.
TEST(MotionRegions, ARegionWhoseUnaryPrefersBackgroundStaysOut) {
  const cv::Mat evidence = evidenceWith({kBox}, 2.0f);
  for (const float unary_in_box : {-0.5f, 0.f, 0.5f}) {
    const cv::Mat unary = evidenceWith({kBox}, unary_in_box);
    MotionRegions regions;
    cv::Mat mask = cv::Mat::zeros(evidence.size(), CV_8U);
    regions.add(evidence, unary, 150, &mask);
    EXPECT_EQ(regions.add(evidence, unary, 150, &mask), unary_in_box > 0 ? 1 : 0) << unary_in_box;
    EXPECT_EQ(cv::countNonZero(mask), unary_in_box > 0 ? 100 : 0) << unary_in_box;
    cv::Mat picture;
    regions.draw(&picture);  // drawn only when taken or first seen
    EXPECT_EQ(cv::countNonZero(picture), unary_in_box > 0 ? 100 : 0) << unary_in_box;
  }
}

// A pair with no camera fitted comes between: the next region is a first sighting again.
TEST(MotionRegions, ForgettingMakesTheNextRegionAFirstSighting) {
  MotionRegions regions;
  const cv::Mat evidence = evidenceWith({kBox}, 2.0f);
  cv::Mat mask = cv::Mat::zeros(evidence.size(), CV_8U);
  regions.add(evidence, evidence, 150, &mask);
  regions.forget(evidence.size());
  EXPECT_EQ(regions.add(evidence, evidence, 150, &mask), 0);
  EXPECT_EQ(regions.add(evidence, evidence, 150, &mask), 1);
}

// A region that touches the mask, even at a corner only, is the outline the cut chose for a mover
// it found: it stays out; an 8-connected region is one region, its sum taken whole.
TEST(MotionRegions, ARegionTouchingTheMaskStaysOutAndDiagonalsConnect) {
  MotionRegions regions;
  cv::Mat evidence = evidenceWith({kBox}, 2.0f);
  cv::Mat mask = cv::Mat::zeros(evidence.size(), CV_8U);
  mask.at<uchar>(9, 9) = 255;  // the box's top-left corner's diagonal neighbour
  regions.add(evidence, evidence, 150, &mask);
  EXPECT_EQ(regions.add(evidence, evidence, 150, &mask), 0);
  EXPECT_EQ(cv::countNonZero(mask), 1);

  // Two 6x6 boxes at 2 (72 each) meeting at a corner: one region of 144, over 100.
  evidence = evidenceWith({cv::Rect(30, 30, 6, 6), cv::Rect(36, 36, 6, 6)}, 2.0f);
  mask.setTo(0);
  MotionRegions joined;
  joined.add(evidence, evidence, 100, &mask);
  EXPECT_EQ(joined.add(evidence, evidence, 100, &mask), 1);
  EXPECT_EQ(cv::countNonZero(mask), 72);
}

}  // namespace
}  // namespace movseg
