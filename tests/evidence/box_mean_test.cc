#include "evidence/box_mean.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "evidence/random_image.h"
#include "test_support.h"

namespace movseg {
namespace {

cv::Mat openCvsMean(const cv::Mat& image) {
  cv::Mat mean;
  cv::blur(image, mean, cv::Size(5, 5));
  return mean;
}

void expectOpenCvsMean(const cv::Mat& image, const std::string& what) {
  BoxMean5 box;
  cv::Mat ours;
  box.apply(image, &ours);
  const cv::Mat opencv = openCvsMean(image);
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  ASSERT_EQ(ours.type(), opencv.type()) << what;
  EXPECT_EQ(cv::countNonZero(ours != opencv), 0) << what;
}

// Every sum a 5x5 window of bytes can have, 0 to 25 x 255, at the centre of a 5x5 image (the
// whole window inside it), and the same windows reflected at its borders.
TEST(BoxMean5, RoundsEverySumAsOpenCv) {
  BoxMean5 box;
  cv::Mat ours;
  for (int sum = 0; sum <= 25 * 255; ++sum) {
    cv::Mat image(5, 5, CV_8U, cv::Scalar(sum / 25));
    for (int i = 0; i < sum % 25; ++i) ++image.at<uchar>(i / 5, i % 5);
    box.apply(image, &ours);
    const cv::Mat opencv = openCvsMean(image);
    ASSERT_EQ(ours.at<uchar>(2, 2), cvRound(sum / 25.0)) << "sum " << sum;
    ASSERT_EQ(cv::countNonZero(ours != opencv), 0) << "sum " << sum;
  }
}

// Random pixels (every byte, and bright ones, whose sums are the largest) over sizes with and
// without the full vectors of 16 and 8 pixels, and smaller than the window: the reflected border
// then reflects more than once.
TEST(BoxMean5, AgreesWithOpenCvOnRandomImagesOfEverySize) {
  const cv::Size sizes[] = {{1, 1},  {2, 2},  {3, 3},  {4, 4},    {5, 5},    {1, 9},
                            {9, 1},  {2, 7},  {16, 3}, {17, 5},   {24, 24},  {31, 33},
                            {8, 40}, {7, 1000}, {1000, 7}, {320, 240}, {321, 241}};
  for (const cv::Size size : sizes) {
    const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height);
    expectOpenCvsMean(randomImage(size, 1), what);
    expectOpenCvsMean(randomImage(size, 2, 200, 256), what + " bright");
    expectOpenCvsMean(cv::Mat(size, CV_8U, cv::Scalar(255)), what + " white");
  }
}

// The mean may be written into a view of a larger image. (The image itself may not be one:
// cv::blur would read the pixels around it for its border.)
TEST(BoxMean5, WritesIntoAView) {
  const cv::Mat image = randomImage({50, 40}, 3);
  cv::Mat out_large(60, 70, CV_8U, cv::Scalar(0));
  cv::Mat out = out_large(cv::Rect(5, 7, 50, 40));
  BoxMean5 box;
  box.apply(image, &out);
  EXPECT_EQ(out.data, out_large.ptr(7) + 5) << "written in place";
  EXPECT_EQ(cv::countNonZero(out != openCvsMean(image)), 0);
  EXPECT_THROW(box.apply(out_large(cv::Rect(1, 1, 10, 10)), &out), cv::Exception);
}

TEST(BoxMean5, AgreesWithOpenCvOnDavisFrames) {
  const std::vector<std::string> files = test::davisFrames("dog", 3);
  if (files.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  for (const std::string& file : files) {
    const cv::Mat grey = cv::imread(file, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(grey.empty()) << file;
    expectOpenCvsMean(grey, file);
    cv::Mat small;
    cv::resize(grey, small, {320, 240}, 0, 0, cv::INTER_AREA);
    expectOpenCvsMean(small, file + " at 320x240");
  }
}

}  // namespace
}  // namespace movseg
