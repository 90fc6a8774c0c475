#include "evidence/bilinear_remap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "evidence/random_image.h"
#include "flow/dense_flow.h"
#include "flow/flow_camera.h"
#include "test_support.h"

namespace movseg {
namespace {

constexpr int kBorders[] = {cv::BORDER_REPLICATE, cv::BORDER_CONSTANT};

std::string borderName(int border) {
  return border == cv::BORDER_REPLICATE ? "replicate" : "constant";
}

// The same pixels, of the same size and type; where they differ, the first few are named with
// the map's point there.
void expectIdentical(const cv::Mat& ours, const cv::Mat& opencv, const cv::Mat& map,
                     const std::string& what) {
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  ASSERT_EQ(ours.type(), opencv.type()) << what;
  const int differing = cv::countNonZero(ours != opencv);
  EXPECT_EQ(differing, 0) << what;
  int named = 0;
  for (int y = 0; y < ours.rows && named < 5; ++y) {
    for (int x = 0; x < ours.cols && named < 5; ++x) {
      if (ours.at<uchar>(y, x) == opencv.at<uchar>(y, x)) continue;
      ++named;
      const auto at = map.at<cv::Vec2f>(y, x);
      ADD_FAILURE() << what << ": (" << x << ", " << y << ") from (" << at[0] << ", " << at[1]
                    << "): " << int{ours.at<uchar>(y, x)} << " against OpenCV's "
                    << int{opencv.at<uchar>(y, x)};
    }
  }
}

// `image` through `map` by BilinearRemap and by cv::remap, with `border`.
void expectOpenCvsRemap(const cv::Mat& image, const cv::Mat& map, int border,
                        const std::string& what) {
  BilinearRemap remap;
  remap.setSource(image, border);
  cv::Mat ours, opencv;
  remap.remap(map, &ours);
  cv::remap(image, opencv, map, cv::noArray(), cv::INTER_LINEAR, border, cv::Scalar(0));
  expectIdentical(ours, opencv, map, what + " " + borderName(border));
}

void expectOpenCvsRemap(const cv::Mat& image, const cv::Mat& map, const std::string& what) {
  for (const int border : kBorders) expectOpenCvsRemap(image, map, border, what);
}

// Pixels that are 0 or 255 only: the largest differences within a neighbourhood, where a weight
// off by one shows most.
cv::Mat blackAndWhite(cv::Size size, uint64 seed) {
  cv::Mat image = randomImage(size, seed, 0, 2);
  return image * 255;
}

cv::Mat identityMap(cv::Size size) {
  cv::Mat map;
  cameraMap(cv::Matx33d::eye(), size, &map);
  return map;
}

// The identity plus a random displacement of up to `reach` pixels along each axis.
cv::Mat randomMap(cv::Size size, float reach, uint64 seed) {
  cv::Mat displacement(size, CV_32FC2);
  cv::RNG(seed).fill(displacement, cv::RNG::UNIFORM, cv::Scalar::all(-reach),
                     cv::Scalar::all(reach));
  return identityMap(size) + displacement;
}

// A map holding `points` row after row, `width` of them per row (the last row padded with the
// first point).
cv::Mat mapOf(const std::vector<cv::Vec2f>& points, int width) {
  const int rows = static_cast<int>((points.size() + static_cast<size_t>(width) - 1) / width);
  cv::Mat map(rows, width, CV_32FC2, cv::Scalar(points[0][0], points[0][1]));
  for (size_t i = 0; i < points.size(); ++i) {
    map.at<cv::Vec2f>(static_cast<int>(i) / width, static_cast<int>(i) % width) = points[i];
  }
  return map;
}

// Every pair of OpenCV's 1/32-pixel fractions, at pixels inside the image and on its borders.
TEST(BilinearRemap, AgreesWithOpenCvAtEveryFraction) {
  const cv::Size size(23, 17);
  std::vector<cv::Vec2f> points;
  for (const cv::Point2f at : {cv::Point2f(5, 7), cv::Point2f(0, 0), cv::Point2f(-1, 3),
                               cv::Point2f(21, 16), cv::Point2f(22, 8), cv::Point2f(10, -1)}) {
    for (int fy = 0; fy < 32; ++fy) {
      for (int fx = 0; fx < 32; ++fx) points.emplace_back(at.x + fx / 32.f, at.y + fy / 32.f);
    }
  }
  const cv::Mat map = mapOf(points, 61);  // not a multiple of the eight points done together
  for (uint64 seed = 1; seed <= 3; ++seed) {
    expectOpenCvsRemap(randomImage(size, seed), map, "random pixels");
    expectOpenCvsRemap(blackAndWhite(size, seed), map, "black and white");
  }
}

// Coordinates on OpenCV's rounding boundaries (half of 1/32 pixel: ties to even), on the image's
// edges and just past them, far outside on every side, and what a float can hold beyond that:
// infinities, NaN, values whose fixed point overflows an int or whose pixel overflows a short.
TEST(BilinearRemap, AgreesWithOpenCvAtBoundariesAndOutside) {
  const cv::Size size(40, 30);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> xs = {
      0.f, 0.5f / 32, 1.5f / 32, 2.5f / 32, 31.5f / 32, -0.5f / 32, -1.5f / 32, -0.5f, 0.5f,
      -1.f, -1.f + 0.5f / 32, -1.5f, -2.f, -2.5f, -3.f, -7.25f, 38.f, 38.5f, 39.f, 39.f + 0.5f / 32,
      39.5f, 39.99f, 40.f, 40.5f, 41.f, 41.5f, 100.f, -100.f, 1023.97f, 32767.f, 32768.5f,
      -32768.f, -32769.f, 67108863.f, 67108864.f, 1e9f, -1e9f, 3e38f, -3e38f, inf, -inf, nan,
      std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min()};
  const std::vector<float> ys = {0.f,   0.5f / 32, 1.5f / 32, -0.5f,  -1.f,  -1.5f, -2.f,
                                 -3.5f, 28.f,      28.5f,     29.f,   29.5f, 30.f,  31.f,
                                 50.f,  1e9f,      -1e9f,     inf,    -inf,  nan,   2.5f / 32};
  std::vector<cv::Vec2f> points;
  for (const float y : ys) {
    for (const float x : xs) points.emplace_back(x, y);
  }
  const cv::Mat map = mapOf(points, 37);
  for (uint64 seed = 1; seed <= 3; ++seed) {
    expectOpenCvsRemap(randomImage(size, seed), map, "random pixels");
    expectOpenCvsRemap(blackAndWhite(size, seed), map, "black and white");
  }
}

// Textures through random flows: small ones (mostly inside), large ones (many points outside).
TEST(BilinearRemap, AgreesWithOpenCvOnTexturesThroughRandomFlows) {
  const cv::Size size(96, 72);
  for (uint64 seed = 1; seed <= 4; ++seed) {
    const cv::Mat image = test::greyTexture(size, seed);
    for (const float reach : {0.5f, 3.f, 40.f, 300.f}) {
      expectOpenCvsRemap(image, randomMap(size, reach, seed + 10),
                         "reach " + std::to_string(reach));
    }
  }
}

// The identity, and a camera's maps as cameraMap() makes them: a zoom with a rotation, a
// perspective, and one whose horizon crosses the frame at column 64: points at infinity and,
// where the numerator is 0 too, NaN; huge coordinates beside them.
TEST(BilinearRemap, AgreesWithOpenCvThroughIdentityAndHomographies) {
  const cv::Size size(120, 90);
  const cv::Mat image = test::greyTexture(size, 7);
  expectOpenCvsRemap(image, identityMap(size), "identity");
  cv::Mat map;
  cameraMap(cv::Matx33d(1.05, -0.08, 3.3, 0.07, 0.98, -2.1, 0, 0, 1), size, &map);
  expectOpenCvsRemap(image, map, "similarity");
  cameraMap(cv::Matx33d(1, 0.1, -4, 0.02, 1.1, 2, 0.0004, 0.0002, 1), size, &map);
  expectOpenCvsRemap(image, map, "mild perspective");
  cameraMap(cv::Matx33d(0, 0, 0, 0, 1, 0, 1.0 / 64, 0, -1), size, &map);
  const cv::Vec2f horizon = map.at<cv::Vec2f>(0, 64), below = map.at<cv::Vec2f>(5, 64);
  ASSERT_TRUE(std::isnan(horizon[0]) && std::isnan(horizon[1]) && std::isinf(below[1]));
  expectOpenCvsRemap(image, map, "horizon");
}

// Images as small as a pixel and as thin as one, maps of other sizes than the image.
TEST(BilinearRemap, AgreesWithOpenCvOnTinyAndThinImages) {
  const cv::Size sizes[] = {{1, 1}, {2, 2}, {5, 5}, {1, 9}, {9, 1}, {3, 2}, {7, 1000}, {1000, 7}};
  for (const cv::Size size : sizes) {
    const cv::Mat image = randomImage(size, 100 + static_cast<uint64>(size.area()));
    const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height);
    expectOpenCvsRemap(image, randomMap(size, 3.f, 5), what);
    for (const cv::Size map_size : {cv::Size(1, 1), cv::Size(13, 3), cv::Size(8, 2)}) {
      cv::Mat map(map_size, CV_32FC2);
      cv::RNG(9).fill(map, cv::RNG::UNIFORM, cv::Scalar::all(-3),
                      cv::Scalar(size.width + 3, size.height + 3));
      expectOpenCvsRemap(image, map, what + " map " + std::to_string(map_size.width));
    }
  }
}

// Views into larger images: the source's border is its own (cv::remap reads nothing beyond a
// view), the map's rows are read at its step, and the output is written at its own.
TEST(BilinearRemap, AgreesWithOpenCvOnViews) {
  const cv::Mat large = test::greyTexture({100, 80}, 3);
  const cv::Mat image = large(cv::Rect(10, 12, 50, 40));
  const cv::Mat large_map = randomMap({90, 70}, 6.f, 4);
  const cv::Mat map = large_map(cv::Rect(3, 5, 61, 45));
  expectOpenCvsRemap(image, map, "views");
  BilinearRemap remap;
  remap.setSource(image, cv::BORDER_REPLICATE);
  cv::Mat out_large(60, 80, CV_8U, cv::Scalar(7));
  cv::Mat out = out_large(cv::Rect(4, 6, 61, 45)), opencv;
  remap.remap(map, &out);
  cv::remap(image, opencv, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  EXPECT_EQ(out.data, out_large.ptr(6) + 4) << "written in place";
  expectIdentical(out, opencv, map, "into a view");
}

// One object serves images of other sizes one after the other.
TEST(BilinearRemap, ASourceOfAnotherSizeReplacesTheLast) {
  BilinearRemap remap;
  for (const cv::Size size : {cv::Size(64, 48), cv::Size(17, 80), cv::Size(64, 48)}) {
    const cv::Mat image = test::greyTexture(size, 2);
    const cv::Mat map = randomMap(size, 5.f, 3);
    for (const int border : kBorders) {
      remap.setSource(image, border);
      cv::Mat ours, opencv;
      remap.remap(map, &ours);
      cv::remap(image, opencv, map, cv::noArray(), cv::INTER_LINEAR, border, cv::Scalar(0));
      expectIdentical(ours, opencv, map, "reused " + borderName(border));
    }
  }
}

// Two sources of one size through one map in one pass, each with its own border: each gets what
// cv::remap gives it alone. Sources of different sizes are refused.
TEST(BilinearRemap, TwoSourcesThroughOneMapGetOpenCvsRemaps) {
  for (const cv::Size size : {cv::Size(96, 72), cv::Size(13, 5), cv::Size(1, 1)}) {
    const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height);
    const cv::Mat grey = randomImage(size, 1), mask = blackAndWhite(size, 2);
    const cv::Mat map = randomMap(size, 8.f, 3);
    BilinearRemap first, second;
    first.setSource(grey, cv::BORDER_REPLICATE);
    second.setSource(mask, cv::BORDER_CONSTANT);
    cv::Mat first_out, second_out, opencv;
    BilinearRemap::remapBoth(first, second, map, &first_out, &second_out);
    cv::remap(grey, opencv, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    expectIdentical(first_out, opencv, map, what + " first");
    cv::remap(mask, opencv, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    expectIdentical(second_out, opencv, map, what + " second");
  }
  BilinearRemap first, second;
  first.setSource(randomImage({20, 10}, 1), cv::BORDER_REPLICATE);
  second.setSource(randomImage({10, 20}, 1), cv::BORDER_REPLICATE);
  cv::Mat first_out, second_out;
  EXPECT_THROW(BilinearRemap::remapBoth(first, second, randomMap({20, 10}, 1.f, 1), &first_out,
                                        &second_out),
               cv::Exception);
}

// DAVIS frames at the working size through the flow DenseFlow finds between them (the previous
// frame, as the photometric check warps it) and a thresholded frame standing for a mask (as the
// mask is carried).
TEST(BilinearRemap, AgreesWithOpenCvOnDavisFramesThroughTheirFlow) {
  const std::vector<std::string> files = test::davisFrames("dog", 5);
  if (files.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  DenseFlow dense(1);
  cv::Mat previous, flows[2], map;  // two flows in flight, as DenseFlow asks
  int pairs = 0;
  for (size_t t = 0; t < files.size(); ++t) {
    const std::string& file = files[t];
    cv::Mat grey = cv::imread(file, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(grey.empty()) << file;
    cv::resize(grey, grey, {320, 240}, 0, 0, cv::INTER_AREA);
    cv::Mat& flow = flows[t % 2];
    dense.next(grey, &flow);
    if (!flow.empty()) {
      flowMap(flow, &map);
      expectOpenCvsRemap(previous, map, cv::BORDER_REPLICATE, file);
      expectOpenCvsRemap(previous > 100, map, cv::BORDER_CONSTANT, file + " mask");
      ++pairs;
    }
    previous = grey;
  }
  EXPECT_EQ(pairs, static_cast<int>(files.size()) - 1);
}

}  // namespace
}  // namespace movseg
