// The working size: a portrait frame gets the pixels its landscape twin gets.
#include "core/frame.h"

#include <gtest/gtest.h>

namespace movseg {
namespace {

TEST(WorkingSize, IsTheLandscapeTwinsTurnedForAPortraitFrame) {
  EXPECT_EQ(workingSize({854, 480}, 320), cv::Size(320, 180));
  EXPECT_EQ(workingSize({480, 854}, 320), cv::Size(180, 320));
  EXPECT_EQ(workingSize({1080, 1920}, 320), cv::Size(180, 320));
  EXPECT_EQ(workingSize({640, 480}, 320), cv::Size(320, 240));
  EXPECT_EQ(workingSize({480, 640}, 320), cv::Size(240, 320));
  EXPECT_EQ(workingSize({480, 480}, 320), cv::Size(320, 320));
}

TEST(WorkingSize, NeverUpscalesAndKeepsTheFrameAtZero) {
  EXPECT_EQ(workingSize({100, 200}, 320), cv::Size(100, 200));
  EXPECT_EQ(workingSize({480, 854}, 0), cv::Size(480, 854));
  EXPECT_EQ(workingSize({3, 5000}, 320), cv::Size(1, 320));
}

TEST(WorkingSize, PreparesAPortraitFrameAtIt) {
  const cv::Mat portrait(854, 480, CV_8UC3, cv::Scalar(40, 80, 120));
  const PreparedFrame f = prepareFrame(portrait, Params());
  EXPECT_EQ(f.seg_bgr.size(), cv::Size(180, 320));
  EXPECT_EQ(f.small_grey.size(), cv::Size(180, 320));
}

}  // namespace
}  // namespace movseg
