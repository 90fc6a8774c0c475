#include "io/frame_source.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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
  EXPECT_TRUE(inNumberOrder("9.png", "\xc3\xa9t\xc3\xa9.png"));  // UTF-8 after ASCII, as by name
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

// decodeImage decodes JPEG and PNG frames itself (io/jpeg_file.h, io/png_file.h) and leaves other
// formats to OpenCV: every one gives cv::imread's pixels, type and size.
TEST(FrameFiles, DecodeAsImreadDoesInEveryFormat) {
  const test::TempDir dir;
  cv::Mat colour(37, 53, CV_8UC3);
  cv::randu(colour, 0, 256);
  cv::Mat grey, with_alpha, deep;
  cv::extractChannel(colour, grey, 0);
  cv::cvtColor(colour, with_alpha, cv::COLOR_BGR2BGRA);
  colour.convertTo(deep, CV_16UC3, 257);
  const std::pair<std::string, cv::Mat> files[] = {
      {"colour.png", colour}, {"grey.png", grey},   {"alpha.png", with_alpha},
      {"deep.png", deep},     {"colour.jpg", colour}, {"grey.jpg", grey},
      {"colour.bmp", colour}};
  for (const auto& [name, image] : files) {
    ASSERT_TRUE(cv::imwrite(dir / name, image)) << name;
  }
  ASSERT_TRUE(cv::imwrite(dir / "progressive.jpg", colour, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  ASSERT_TRUE(cv::imwrite(dir / "bilevel.png", grey > 128, {cv::IMWRITE_PNG_BILEVEL, 1}));
  for (const std::string& path : listImages(dir.path())) {
    SCOPED_TRACE(path);
    for (const int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_GRAYSCALE, cv::IMREAD_COLOR}) {
      const cv::Mat ours = decodeImage(path, flags), theirs = cv::imread(path, flags);
      ASSERT_FALSE(ours.empty()) << flags;
      EXPECT_EQ(ours.size(), theirs.size()) << flags;
      ASSERT_EQ(ours.type(), theirs.type()) << flags;
      EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0) << flags;
    }
  }
}

}  // namespace
}  // namespace movseg
