#include "io/frame_source.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

namespace movseg {
namespace {

TEST(FrameOrder, DigitsCompareAsNumbers) {
  EXPECT_TRUE(inNumberOrder("f/2.png", "f/10.png"));
  EXPECT_FALSE(inNumberOrder("f/10.png", "f/2.png"));
  EXPECT_TRUE(inNumberOrder("f/00009.png", "f/00010.png"));  // padded: as by name
  EXPECT_TRUE(inNumberOrder("cam1_frame9.jpg", "cam1_frame10.jpg"));
  EXPECT_TRUE(inNumberOrder("cam1_frame10.jpg", "cam2_frame1.jpg"));  // the first number first
  EXPECT_TRUE(inNumberOrder("a.png", "b.png"));
  EXPECT_TRUE(inNumberOrder("frame.png", "frame1.png"));  // a prefix first
  // Equal in value, different in name: ordered all the same (a strict weak order).
  EXPECT_NE(inNumberOrder("01.png", "1.png"), inNumberOrder("1.png", "01.png"));
  EXPECT_FALSE(inNumberOrder("7.png", "7.png"));
}

// Frames named without padding (1.png ... 11.png) are read 1, 2, ..., 11, not 1, 10, 11, 2:
// each frame here is as wide as its number.
TEST(FrameOrder, AFolderOfUnpaddedNamesIsReadInNumberOrder) {
  const test::TempDir dir;
  for (int n = 1; n <= 11; ++n) {
    const cv::Mat frame(4, n, CV_8UC3, cv::Scalar::all(0));
    cv::imwrite(dir / (std::to_string(n) + ".png"), frame);
  }
  const std::unique_ptr<FrameSource> source = FrameSource::open(dir.path());
  std::vector<int> widths;
  cv::Mat frame;
  while (source->read(&frame)) widths.push_back(frame.cols);
  EXPECT_EQ(widths, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
}

}  // namespace
}  // namespace movseg
