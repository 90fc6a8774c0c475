#include "flow/flow_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>

#include <opencv2/imgproc.hpp>

#include "motion/model.h"
#include "test_support.h"

namespace movseg {
namespace {

// One pair's camera, by a fitter of its own.
FlowCamera fitFlowCamera(const cv::Mat& flow, const std::vector<GridSample>& grid,
                         const cv::Mat& moving, const Params& params, cv::RNG& rng,
                         const cv::Matx33d* previous_model = nullptr) {
  FlowCamera camera;
  FlowCameraFitter(params).fit(flow, grid, moving, rng, previous_model, &camera);
  return camera;
}

// The texture measured at the samples alone is OpenCV's, inside the frame and on its borders
// and corners, where both reflect the image.
TEST(FlowCamera, TextureAtAPixelIsCornerMinEigenValsThere) {
  const cv::Mat grey = test::greyTexture({61, 47}, 3);
  cv::Mat expected;
  cv::cornerMinEigenVal(grey, expected, 5);
  double largest = 0;
  cv::minMaxLoc(expected, nullptr, &largest);
  ASSERT_GT(largest, 1e-4);
  for (const cv::Point p : {cv::Point(30, 20), cv::Point(0, 0), cv::Point(60, 46), cv::Point(1, 45),
                            cv::Point(59, 0), cv::Point(7, 13)}) {
    EXPECT_NEAR(minEigenValueAt(grey, p), expected.at<float>(p), 1e-5 * largest) << p;
  }
}

// minEigenValueAt as it was written first, every derivative read through reflected indices:
// the reference its faster reading inside the frame must match to the bit.
float reflectedMinEigenValue(const cv::Mat& grey, cv::Point p) {
  auto reflected = [](int v, int n) { return cv::borderInterpolate(v, n, cv::BORDER_REFLECT_101); };
  std::int64_t xx = 0, xy = 0, yy = 0;
  for (int j = -2; j <= 2; ++j) {
    for (int i = -2; i <= 2; ++i) {
      const int y = reflected(p.y + j, grey.rows), x = reflected(p.x + i, grey.cols);
      auto at = [&](int dy, int dx) {
        return int{grey.at<uchar>(reflected(y + dy, grey.rows), reflected(x + dx, grey.cols))};
      };
      const int gx = (at(-1, 1) - at(-1, -1)) + 2 * (at(0, 1) - at(0, -1)) + (at(1, 1) - at(1, -1));
      const int gy = (at(1, -1) - at(-1, -1)) + 2 * (at(1, 0) - at(-1, 0)) + (at(1, 1) - at(-1, 1));
      xx += gx * gx;
      xy += gx * gy;
      yy += gy * gy;
    }
  }
  constexpr double kScale = 1.0 / (4 * 5 * 255.0);
  const double a = static_cast<double>(xx) * kScale * kScale / 2;
  const double b = static_cast<double>(xy) * kScale * kScale;
  const double c = static_cast<double>(yy) * kScale * kScale / 2;
  return static_cast<float>((a + c) - std::sqrt((a - c) * (a - c) + b * b));
}

// At every pixel of textures, of noise and of black-and-white noise (the largest derivatives),
// on frames of several sizes: the same float as the reference, inside and on the borders.
TEST(FlowCamera, TextureAtEveryPixelIsTheReflectedReadings) {
  const cv::Size sizes[] = {{61, 47}, {8, 8}, {7, 9}, {16, 5}, {320, 240}};
  for (const cv::Size size : sizes) {
    cv::Mat noise(size, CV_8U), extremes(size, CV_8U);
    cv::RNG(8).fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::RNG(9).fill(extremes, cv::RNG::UNIFORM, 0, 2);
    extremes *= 255;
    for (const cv::Mat& grey : {test::greyTexture(size, 3), noise, extremes}) {
      int differing = 0;
      for (int y = 0; y < size.height; ++y) {
        for (int x = 0; x < size.width; ++x) {
          differing += minEigenValueAt(grey, {x, y}) != reflectedMinEigenValue(grey, {x, y});
        }
      }
      EXPECT_EQ(differing, 0) << size;
    }
  }
}

// A camera that zooms and pans, as a flow field (current -> previous), and a square that moves
// on its own, marked as moving: the fit finds the camera, the residual is the square's motion
// there and nothing elsewhere.
TEST(FlowCamera, FitsTheCameraAroundAMarkedMoverAndLeavesItsMotionAsResidual) {
  const cv::Size size(160, 120);
  const cv::Matx33d camera(1.02, 0.01, -2.5, -0.01, 1.02, 1.5, 0, 0, 1);
  const cv::Rect mover(60, 40, 30, 30);
  cv::Mat flow(size, CV_32FC2), moving = cv::Mat::zeros(size, CV_8U);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const cv::Point2f p(static_cast<float>(x), static_cast<float>(y));
      const cv::Point2f to =
          applyModel(camera, p) + (mover.contains({x, y}) ? cv::Point2f(4, -3) : cv::Point2f());
      flow.at<cv::Vec2f>(y, x) = cv::Vec2f(to.x - p.x, to.y - p.y);
    }
  }
  moving(mover).setTo(255);
  cv::RNG rng(1);
  const Params params;
  std::vector<GridSample> samples;
  gridSamples(test::greyTexture(size, 4), params.flow_sample_step, cv::Mat(), &samples);
  const FlowCamera fit = fitFlowCamera(flow, samples, moving, params, rng);
  ASSERT_FALSE(fit.fallback);
  EXPECT_LT(cv::norm(cv::Matx33d(fit.model * (1.0 / fit.model(2, 2))) - camera), 1e-3);
  cv::Mat flow_map, camera_map, residual;
  flowMap(flow, &flow_map);
  cameraMap(fit.model, size, &camera_map);
  residualMotion(flow_map, camera_map, &residual);
  EXPECT_NEAR(residual.at<float>(55, 75), 5.0, 0.01);  // |(4, -3)|
  EXPECT_NEAR(residual.at<float>(10, 10), 0.0, 0.01);
  EXPECT_NEAR(residual.at<float>(110, 150), 0.0, 0.01);
}

// Two halves of the view, mirror images of each other, each moving as a plane of its own: they
// support the two motions exactly as well, and the fit keeps the one of the last pair (the warm
// start) whichever it is and whatever the random draws. Without it, one draw picks one plane for
// both.
TEST(FlowCamera, OfTwoEquallySupportedPlanesTheLastPairsIsKept) {
  const cv::Size half(80, 120);  // 161 wide: the samples (every 8 px from 4) mirror onto samples
  const cv::Mat left = test::greyTexture(half, 5);
  cv::Mat right, grey;
  cv::flip(left, right, 1);
  cv::hconcat(std::vector<cv::Mat>{left, cv::Mat(half.height, 1, CV_8U, cv::Scalar(128)), right},
              grey);
  const cv::Matx33d a(1, 0, 4, 0, 1, 0, 0, 0, 1), b(1, 0, -4, 0, 1, 1, 0, 0, 1);
  cv::Mat flow(grey.size(), CV_32FC2);
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      const cv::Matx33d& m = x <= 80 ? a : b;
      flow.at<cv::Vec2f>(y, x) =
          cv::Vec2f(static_cast<float>(m(0, 2)), static_cast<float>(m(1, 2)));
    }
  }
  const Params params;
  std::vector<GridSample> samples;
  gridSamples(grey, params.flow_sample_step, cv::Mat(), &samples);
  for (const cv::Matx33d& last : {a, b}) {
    for (const std::uint64_t seed : {1u, 2u, 3u, 4u}) {
      cv::RNG rng(seed);
      const FlowCamera fit = fitFlowCamera(flow, samples, cv::Mat(), params, rng, &last);
      ASSERT_FALSE(fit.fallback);
      EXPECT_LT(cv::norm(cv::Matx33d(fit.model * (1.0 / fit.model(2, 2))) - last), 1e-3)
          << "seed " << seed << ", last pair's x shift " << last(0, 2);
    }
  }
}

// The fit of a flow field (current -> previous) of `size`, given per pixel.
FlowCamera fitOf(cv::Size size, const std::function<cv::Point2f(int x, int y)>& flow_at) {
  cv::Mat flow(size, CV_32FC2);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const cv::Point2f f = flow_at(x, y);
      flow.at<cv::Vec2f>(y, x) = cv::Vec2f(f.x, f.y);
    }
  }
  cv::RNG rng(1);
  const Params params;
  std::vector<GridSample> samples;
  gridSamples(test::greyTexture(size, 4), params.flow_sample_step, cv::Mat(), &samples);
  const FlowCamera fit = fitFlowCamera(flow, samples, cv::Mat(), params, rng);
  EXPECT_FALSE(fit.fallback);
  return fit;
}

// Whether the fit reads depth.
bool readsDepth(cv::Size size, const std::function<cv::Point2f(int x, int y)>& flow_at) {
  return fitOf(size, flow_at).epipole.has_value();
}

// A camera moving sideways: the far wall's flow is 2 px to the right, and the rows of a 160x120
// view from `top` down move `strip(y - top)`.
FlowCamera fitOfStrip(int top, const std::function<cv::Point2f(int)>& strip) {
  return fitOf({160, 120},
               [&](int, int y) { return y < top ? cv::Point2f(2, 0) : strip(y - top); });
}

// The lowest 30 % of the rows: a strip too small to show depth everywhere (under 28 cells).
bool readsDepthOfStrip(const std::function<cv::Point2f(int)>& strip) {
  return fitOfStrip(84, strip).epipole.has_value();
}

// The same wall in a 320x240 view with three near posts 8 px wide from top to bottom, post i
// moving `post(i)`: about 7 % of the samples (under the tenth of kDepthWithThePlane), over 24
// cells.
bool readsDepthOfPosts(const std::function<cv::Point2f(int)>& post) {
  return readsDepth({320, 240}, [&](int x, int) {
    const bool on_post = x % 100 >= 50 && x % 100 < 58;
    return on_post ? post(x / 100) : cv::Point2f(2, 0);
  });
}

// Posts that all move with the plane, only further, agree on the epipole: depth, though they
// are few.
TEST(FlowCamera, AFewNearPostsThatAgreeAreDepth) {
  EXPECT_TRUE(readsDepthOfPosts([](int) { return cv::Point2f(4, 0); }));
}

// As few posts whose motions point two ways (two of three agree): too few, agreeing too little.
TEST(FlowCamera, AFewNearPostsThatDisagreeAreNotDepth) {
  EXPECT_FALSE(readsDepthOfPosts([](int i) { return cv::Point2f(4, i == 1 ? -1.5f : 1.5f); }));
}

// Near ground below the wall moves with it, only further the nearer (parallax 1.5 to 4.3 px):
// depth, read although it covers little of the view.
TEST(FlowCamera, NearGroundMovingWithThePlaneIsDepth) {
  EXPECT_TRUE(readsDepthOfStrip([](int row) { return cv::Point2f(3.5f + 0.08f * row, 0); }));
}

// The same strip standing still in the image — a mover the camera follows — moves against the
// plane: not depth, however well its motion agrees on an epipole.
TEST(FlowCamera, AMoverTheCameraFollowsIsNotDepth) {
  EXPECT_FALSE(readsDepthOfStrip([](int) { return cv::Point2f(0, 0); }));
}

// The plane at a middle depth: the near ground below it moves further than it, a far band
// above it (at infinity) not at all, against it; both along lines through one epipole. Two in
// five of those agreeing move against the plane (kDepthWithThePlane allows one in four at
// most), the share and the cells are under kDepthEverywhere's: depth, read by the rule that
// asks for agreement. Asking there for three quarters with the plane, as before, fails this.
TEST(FlowCamera, AStaticSceneOnBothSidesOfThePlaneIsDepth) {
  const FlowCamera fit = fitOf({160, 120}, [](int, int y) {
    if (y < 15) return cv::Point2f(0, 0);
    return y < 96 ? cv::Point2f(2, 0) : cv::Point2f(3.5f + 0.08f * (y - 96), 0);
  });
  ASSERT_TRUE(fit.epipole.has_value());
  EXPECT_TRUE(fit.depth_with_the_plane);
}

// Which rule read depth: the near ground moves with the plane; bands above and below the wall
// standing still (45 % of the rows, 32 cells) show depth everywhere, against the plane, as a
// large mover the camera follows would.
TEST(FlowCamera, DepthSaysWhetherItMovedWithThePlane) {
  const FlowCamera ground =
      fitOfStrip(84, [](int row) { return cv::Point2f(3.5f + 0.08f * row, 0); });
  ASSERT_TRUE(ground.epipole.has_value());
  EXPECT_TRUE(ground.depth_with_the_plane);
  const FlowCamera still = fitOf({160, 120}, [](int, int y) {
    return y < 27 || y >= 93 ? cv::Point2f(0, 0) : cv::Point2f(2, 0);
  });
  ASSERT_TRUE(still.epipole.has_value());
  EXPECT_FALSE(still.depth_with_the_plane);
}

// A static scene with depth explains a flow by any point of the pixel's epipolar line: moved
// there, the camera's map leaves the flow's part across the line as the residual. An epipole
// inside the view (a camera moving forwards) and one at infinity (sideways).
TEST(FlowCamera, AlongEpipolarLinesLeavesTheMotionAcrossTheLine) {
  const cv::Size size(8, 6);
  cv::Mat camera_map, flow_map(size, CV_32FC2), residual;
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  // From the epipole (2, 3): 1.5 px outwards along the line and 0.5 px across it at every pixel
  // but the epipole's own, whose line has no direction: its flow is all residual.
  const cv::Point2f epipole(2, 3);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const cv::Point2f p(static_cast<float>(x), static_cast<float>(y));
      const cv::Point2f outwards =
          p == epipole ? cv::Point2f(1, 0) : (p - epipole) / cv::norm(p - epipole);
      const cv::Point2f across(-outwards.y, outwards.x);
      flow_map.at<cv::Point2f>(y, x) = p + 1.5f * outwards + 0.5f * across;
    }
  }
  alongEpipolarLines(flow_map, cv::Vec3d(2, 3, 1), &camera_map);
  residualMotion(flow_map, camera_map, &residual);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const cv::Point2f p(static_cast<float>(x), static_cast<float>(y));
      const cv::Point2f on_line = camera_map.at<cv::Point2f>(y, x);
      if (p == epipole) {
        EXPECT_EQ(on_line, p);
        EXPECT_NEAR(residual.at<float>(y, x), std::hypot(1.5, 0.5), 1e-5);
        continue;
      }
      EXPECT_NEAR(residual.at<float>(y, x), 0.5, 1e-5) << p;
      EXPECT_NEAR(cv::norm(on_line - p), 1.5, 1e-5) << p;
    }
  }
  // At infinity along x: the lines are the rows, a flow of (5, -3) leaves 3 px.
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      flow_map.at<cv::Point2f>(y, x) =
          cv::Point2f(static_cast<float>(x) + 5, static_cast<float>(y) - 3);
    }
  }
  alongEpipolarLines(flow_map, cv::Vec3d(1, 0, 0), &camera_map);
  residualMotion(flow_map, camera_map, &residual);
  EXPECT_EQ(camera_map.at<cv::Point2f>(4, 6), cv::Point2f(11, 4));
  EXPECT_NEAR(cv::norm(residual, cv::NORM_INF), 3.0, 1e-6);
  EXPECT_NEAR(cv::norm(residual, cv::NORM_L1), 3.0 * size.area(), 1e-4);
}

}  // namespace
}  // namespace movseg
