// The mask's outline snapped to the image's edges: the guided filter it is, and what it does.
#include <algorithm>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>

#include "refine/edge_snap.h"

namespace movseg {
namespace {

// A smooth random texture (8-bit BGR), as the frames' surfaces.
cv::Mat texture(cv::Size size, int seed) {
  cv::Mat noise(size, CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(7, 7), 2.0);
  return noise;
}

cv::Mat grey(const cv::Mat& bgr) {
  cv::Mat out;
  cv::cvtColor(bgr, out, cv::COLOR_BGR2GRAY);
  return out;
}

TEST(EdgeSnap, IsOpenCvsGuidedFilterOfTheMaskButOnItsThinParts) {
  for (int seed = 0; seed < 4; ++seed) {
    const cv::Mat bgr = texture({96, 64}, seed);
    cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
    cv::circle(mask, {30 + 10 * seed, 30}, 14, cv::Scalar(255), -1);
    cv::rectangle(mask, {0, 0}, {20, 12 + seed}, cv::Scalar(255), -1);  // at the border too
    cv::line(mask, {60, 50}, {90, 58}, cv::Scalar(255), 1);              // a thin part
    for (int radius : {1, 2, 4}) {
      const cv::Mat snapped = EdgeSnap().snap(mask, grey(bgr), radius);
      cv::Mat label, reference;
      mask.convertTo(label, CV_32F, 1.0 / 255);
      cv::ximgproc::guidedFilter(grey(bgr), label, reference, radius, EdgeSnap::kRegulariser);
      cv::Mat opened;  // what is left of the mask without its parts too thin for a window
      cv::morphologyEx(mask, opened, cv::MORPH_OPEN,
                       cv::getStructuringElement(cv::MORPH_CROSS, {3, 3}));
      for (int y = 0; y < mask.rows; ++y) {
        for (int x = 0; x < mask.cols; ++x) {
          const bool thin = mask.at<uchar>(y, x) != opened.at<uchar>(y, x);
          const float expected = thin ? 255.f : 255.f * reference.at<float>(y, x);
          ASSERT_NEAR(snapped.at<uchar>(y, x), std::clamp(expected, 0.f, 255.f), 1.0)
              << "seed " << seed << " radius " << radius << " at " << x << "," << y;
        }
      }
    }
  }
}

// A vertical edge at x = 40 and a mask a pixel off it, either way (the cut's 2x2 blocks put an
// outline up to a pixel off at the working scale): the snapped outline is the edge's, in every
// row. (Two pixels off, a radius of 2 moves it part of the way only.)
TEST(EdgeSnap, MovesAnOutlineOntoTheEdgeBesideIt) {
  cv::Mat bgr(48, 80, CV_8UC3, cv::Scalar(60, 60, 60));
  bgr.colRange(40, 80).setTo(cv::Scalar(180, 180, 180));
  cv::Mat noise(bgr.size(), CV_8UC3);
  cv::randn(noise, cv::Scalar::all(0), cv::Scalar::all(2));
  bgr += noise;
  for (int offset : {-1, 1}) {
    cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
    mask.colRange(40 + offset, 80).setTo(255);
    const cv::Mat snapped = EdgeSnap().snap(mask, grey(bgr), 2);
    cv::Mat expected = cv::Mat::zeros(bgr.size(), CV_8U);
    expected.colRange(40, 80).setTo(255);
    EXPECT_EQ(cv::countNonZero((snapped > 127) != expected), 0) << "offset " << offset;
  }
}

TEST(EdgeSnap, LeavesEveryPixelAwayFromTheOutlineAsItWas) {
  const cv::Mat bgr = texture({120, 90}, 7);
  cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
  cv::ellipse(mask, {60, 45}, {30, 20}, 15, 0, 360, cv::Scalar(255), -1);
  const int radius = 3;
  const cv::Mat snapped = EdgeSnap().snap(mask, grey(bgr), radius);
  cv::Mat grown, shrunk;
  const cv::Mat window =
      cv::getStructuringElement(cv::MORPH_RECT, {4 * radius + 1, 4 * radius + 1});
  cv::dilate(mask, grown, window);
  cv::erode(mask, shrunk, window);
  const cv::Mat away = grown == shrunk;  // no outline within two radii
  EXPECT_EQ(cv::countNonZero((snapped != mask) & away), 0);
  EXPECT_GT(cv::countNonZero((snapped > 127) != mask), 0);  // it did move the outline
}

TEST(EdgeSnap, KeepsAPartTooThinForAWindow) {
  const cv::Mat bgr = texture({60, 40}, 3);
  cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
  cv::rectangle(mask, {5, 5}, {25, 30}, cv::Scalar(255), -1);
  cv::line(mask, {25, 18}, {55, 18}, cv::Scalar(255), 1);  // a pole a pixel wide
  const cv::Mat snapped = EdgeSnap().snap(mask, grey(bgr), 2);
  for (int x = 30; x <= 55; ++x) EXPECT_GT(snapped.at<uchar>(18, x), 127) << x;
}

TEST(EdgeSnap, RadiusZeroAndAnEmptyMaskLeaveTheMask) {
  const cv::Mat bgr = texture({40, 30}, 1);
  cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
  EdgeSnap snap;
  EXPECT_EQ(cv::countNonZero(snap.snap(mask, grey(bgr), 2)), 0);
  mask(cv::Rect(10, 10, 12, 9)).setTo(255);
  EXPECT_EQ(cv::countNonZero(snap.snap(mask, grey(bgr), 0) != mask), 0);
}

// A frame three times the working size with a vertical edge at x = 100, a third of the way into
// working column 33 (input 99 to 101), and the working mask's outline a pixel either side of
// that column. Given the frame at its own size, the snapped outline is the edge's in nearly every
// row (sensor noise moves a few pixels); the working result scaled up is a column off in every
// row, the working image having no edge inside its pixel.
TEST(EdgeSnap, OnTheInputsEdgesWhenGivenTheFrameAtItsSize) {
  cv::Mat levels(150, 240, CV_16S, cv::Scalar(60)), noise(150, 240, CV_16S), input;
  levels.colRange(100, 240).setTo(180);
  cv::RNG(7).fill(noise, cv::RNG::NORMAL, 0, 2);
  cv::Mat(levels + noise).convertTo(input, CV_8U);
  cv::Mat working;
  cv::resize(input, working, {80, 50}, 0, 0, cv::INTER_AREA);
  cv::Mat expected = cv::Mat::zeros(input.size(), CV_8U);
  expected.colRange(100, 240).setTo(255);
  for (int start : {33, 34}) {
    cv::Mat mask = cv::Mat::zeros(working.size(), CV_8U);
    mask.colRange(start, 80).setTo(255);
    EdgeSnap snap;
    const cv::Mat on_input = snap.snap(mask, working, 2, input);
    ASSERT_EQ(on_input.size(), input.size());
    EXPECT_LE(cv::countNonZero((on_input > 127) != expected), 5) << "from column " << start;
    cv::Mat scaled_up;
    cv::resize(snap.snap(mask, working, 2), scaled_up, input.size(), 0, 0, cv::INTER_LINEAR);
    EXPECT_GE(cv::countNonZero((scaled_up > 127) != expected), input.rows) << start;
  }
}

// Away from where the filter changes the working mask, the result at the input's size is the
// working result scaled up; given an image of the mask's own size, the working result itself.
TEST(EdgeSnap, AtTheInputsSizeChangesOnlyTheOutline) {
  const cv::Mat bgr = texture({120, 90}, 5);
  cv::Mat mask = cv::Mat::zeros(bgr.size(), CV_8U);
  cv::ellipse(mask, {60, 45}, {30, 20}, 15, 0, 360, cv::Scalar(255), -1);
  cv::line(mask, {90, 45}, {115, 80}, cv::Scalar(255), 1);  // a thin part: kept as it is
  cv::Mat input;
  cv::resize(bgr, input, {}, 2.5, 2.5, cv::INTER_CUBIC);
  EdgeSnap snap;
  // A copy: a snap's result is its own buffer, written again by the next call.
  const cv::Mat working = snap.snap(mask, grey(bgr), 2).clone();
  EXPECT_EQ(cv::countNonZero(snap.snap(mask, grey(bgr), 2, grey(bgr)) != working), 0);
  const cv::Mat on_input = snap.snap(mask, grey(bgr), 2, grey(input));
  cv::Mat scaled_up, changed;
  cv::resize(working, scaled_up, input.size(), 0, 0, cv::INTER_LINEAR);
  cv::dilate(working != mask, changed, cv::Mat(), cv::Point(-1, -1), 2);
  cv::resize(changed, changed, input.size(), 0, 0, cv::INTER_NEAREST);
  EXPECT_EQ(cv::countNonZero((on_input != scaled_up) & ~changed), 0);
  EXPECT_GT(cv::countNonZero(on_input != scaled_up), 0);
  for (int x = 95; x <= 112; ++x) {  // the pole, 2.5 times as far
    const int y = cvRound(45 + (x - 90) * 35.0 / 25);
    EXPECT_GT(on_input.at<uchar>(cvRound(2.5 * y + 0.75), cvRound(2.5 * x + 0.75)), 127) << x;
  }
}

}  // namespace
}  // namespace movseg
