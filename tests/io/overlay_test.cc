// The overlay README promises: the mask tinted red over the frame, the features as dots of their
// label's colour, the heads-up text top-left, and the frame itself everywhere else.
#include "io/overlay.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "test_support.h"

namespace movseg {
namespace {

const cv::Size kSize(160, 120);
const cv::Rect kMoving(60, 50, 40, 40);

Result resultWithFeatures() {
  Result result;
  result.mask = cv::Mat::zeros(kSize, CV_8U);
  result.mask(kMoving).setTo(255);
  result.features = {{{20, 100}, FeatureLabel::kForeground},
                     {{140, 100}, FeatureLabel::kBackground},
                     {{140, 20}, FeatureLabel::kUnknown}};
  return result;
}

// The pixels of `overlay` that differ from `frame`.
cv::Mat changed(const cv::Mat& overlay, const cv::Mat& frame) {
  cv::Mat difference;
  cv::absdiff(overlay, frame, difference);
  cv::Mat any;
  cv::transform(difference, any, cv::Matx13f(1, 1, 1));
  return any > 0;
}

TEST(Overlay, TintsTheMaskAndLeavesTheRestOfTheFrame) {
  const cv::Mat frame = test::texture(kSize, 7);
  const cv::Mat overlay = drawOverlay(frame, resultWithFeatures(), "", false);
  ASSERT_EQ(overlay.size(), kSize);
  ASSERT_EQ(overlay.type(), CV_8UC3);
  // Inside, away from the outline drawn 2 px wide: half the frame, half red.
  const cv::Rect inside(kMoving.x + 3, kMoving.y + 3, kMoving.width - 6, kMoving.height - 6);
  cv::Mat tinted;
  cv::addWeighted(frame(inside), 0.5, cv::Mat(inside.size(), CV_8UC3, cv::Scalar(0, 0, 255)),
                  0.5, 0, tinted);
  EXPECT_EQ(cv::norm(overlay(inside), tinted, cv::NORM_INF), 0.0);
  // Outside the mask and its outline: the frame, untouched.
  cv::Mat untouched = cv::Mat::ones(kSize, CV_8U);
  untouched(cv::Rect(kMoving.x - 3, kMoving.y - 3, kMoving.width + 6, kMoving.height + 6))
      .setTo(0);
  EXPECT_EQ(cv::countNonZero(changed(overlay, frame) & untouched), 0);
}

TEST(Overlay, DrawsFeaturesInTheirLabelsColoursOnlyWhenAsked) {
  const cv::Mat frame(kSize, CV_8UC3, cv::Scalar(90, 90, 90));
  const Result result = resultWithFeatures();
  const cv::Mat dots = drawOverlay(frame, result, "", true);
  EXPECT_EQ(dots.at<cv::Vec3b>(100, 20), cv::Vec3b(0, 0, 255));     // foreground: red
  EXPECT_EQ(dots.at<cv::Vec3b>(100, 140), cv::Vec3b(255, 128, 0));  // background: blue
  EXPECT_EQ(dots.at<cv::Vec3b>(20, 140), cv::Vec3b(0, 255, 255));   // unknown: yellow
  const cv::Mat plain = drawOverlay(frame, result, "", false);
  for (const Feature& f : result.features) {
    EXPECT_EQ(plain.at<cv::Vec3b>(f.position), cv::Vec3b(90, 90, 90)) << f.position;
  }
}

TEST(Overlay, WritesTheHeadsUpTextTopLeft) {
  const cv::Mat frame(kSize, CV_8UC3, cv::Scalar(90, 90, 90));
  Result empty;
  empty.mask = cv::Mat::zeros(kSize, CV_8U);
  const cv::Mat changes = changed(drawOverlay(frame, empty, "frame 12  30.0 fps"), frame);
  const cv::Rect top_left(0, 0, kSize.width, 24);
  EXPECT_GT(cv::countNonZero(changes(top_left)), 50);
  EXPECT_EQ(cv::countNonZero(changes), cv::countNonZero(changes(top_left)));
  EXPECT_EQ(cv::countNonZero(changed(drawOverlay(frame, empty, ""), frame)), 0);
}

}  // namespace
}  // namespace movseg
