// The picture inside letterbox and pillarbox bars: exact on bars with a codec's noise, never on
// dark picture or a dark frame.
#include "core/black_bars.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "test_support.h"

namespace movseg {
namespace {

// A textured picture of `picture`'s size at its place in a black frame of `frame`'s size.
cv::Mat framed(cv::Size frame, const cv::Rect& picture) {
  cv::Mat bgr = cv::Mat::zeros(frame, CV_8UC3);
  test::texture(picture.size(), 7).copyTo(bgr(picture));
  return bgr;
}

TEST(BlackBars, LetterboxPillarboxAndBothAreFoundExactly) {
  for (const cv::Rect& picture : {cv::Rect(0, 30, 320, 180), cv::Rect(40, 0, 240, 240),
                                  cv::Rect(20, 12, 280, 200), cv::Rect(0, 0, 320, 236)}) {
    EXPECT_EQ(pictureInsideBlackBars(framed({320, 240}, picture)), picture) << picture;
  }
}

// A codec leaves the bars near black, not black: noise up to 20, and ringing of up to 60 in the
// line next to the picture, are still bars.
TEST(BlackBars, NoisyBarsAreBars) {
  const cv::Rect picture(0, 30, 320, 180);
  cv::Mat bgr = framed({320, 240}, picture);
  cv::Mat noise(bgr.size(), CV_8UC3);
  cv::randu(noise, 0, 20);
  noise(picture).setTo(0);
  bgr += noise;
  for (int x = 0; x < 320; x += 8) bgr.at<cv::Vec3b>(29, x) = {60, 60, 60};
  EXPECT_EQ(pictureInsideBlackBars(bgr), picture);
}

// Picture that is dark is picture: a night sky with one lamp, a whole black frame (a fade), and
// a frame whose "bars" would leave less than a quarter of it. The frame is a view into a larger
// image, its rows not a whole number of pixels apart.
TEST(BlackBars, DarkPictureIsNoBar) {
  cv::Mat night = framed({320, 240}, {0, 0, 320, 240});
  night.rowRange(0, 40).setTo(cv::Scalar::all(10));
  night.at<cv::Vec3b>(5, 100) = {200, 200, 200};  // a lamp in row 5
  EXPECT_EQ(pictureInsideBlackBars(night), cv::Rect(0, 5, 320, 235));
  EXPECT_EQ(pictureInsideBlackBars(cv::Mat::zeros(240, 320, CV_8UC3)), cv::Rect(0, 0, 320, 240));
  EXPECT_EQ(pictureInsideBlackBars(framed({320, 240}, {0, 100, 320, 50})), cv::Rect(0, 0, 320, 240));
  cv::Mat wide = cv::Mat::zeros(240, 331, CV_8UC1);
  cv::Mat view = cv::Mat(240, 110, CV_8UC3, wide.data, wide.step);  // 331 bytes a row
  test::texture({60, 240}, 3).copyTo(view.colRange(20, 80));
  EXPECT_EQ(pictureInsideBlackBars(view), cv::Rect(20, 0, 60, 240));
}

}  // namespace
}  // namespace movseg
