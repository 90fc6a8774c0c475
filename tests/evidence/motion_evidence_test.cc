#include "evidence/motion_evidence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "flow/dense_flow.h"
#include "flow/flow_camera.h"
#include "test_support.h"

namespace movseg {
namespace {

cv::Mat uniformFlow(cv::Size size, cv::Vec2f motion) {
  return cv::Mat(size, CV_32FC2, cv::Scalar(motion[0], motion[1]));
}

// The check of a pair without a previous mask.
cv::Mat confirmation(const cv::Mat& grey, const cv::Mat& previous, const cv::Mat& flow_map,
                     const cv::Mat& camera_map, const Params& params = Params()) {
  PhotometricCheck check;
  cv::Mat carried, confirmed;
  check.followFlow(previous, cv::Mat(), flow_map, &carried);
  check.confirm(grey, camera_map, LevelMap(), cv::Mat(), params, &confirmed);
  return confirmed;
}

// The previous mask carried as the pipeline carries it, with the previous frame (flat here).
cv::Mat carriedMask(const cv::Mat& previous_mask, const cv::Mat& flow_map) {
  PhotometricCheck check;
  cv::Mat carried;
  check.followFlow(cv::Mat(previous_mask.size(), CV_8U, cv::Scalar(128)), previous_mask, flow_map,
                   &carried);
  return carried;
}

// A textured square moved 3 px right over a still textured background, the flow exact and the
// camera still.
struct MovedSquare {
  const cv::Size size{96, 96};
  const cv::Rect inside{38, 36, 18, 18}, far{0, 70, 96, 26};  // in the square; away from it
  cv::Mat previous, current, flow_map, camera_map;

  MovedSquare() {
    const cv::Mat background = test::greyTexture(size, 1);
    const cv::Mat object = test::greyTexture(size, 2);
    const cv::Rect before(30, 30, 30, 30), after(33, 30, 30, 30);
    previous = background.clone(), current = background.clone();
    object(before).copyTo(previous(before));
    object(before).copyTo(current(after));
    cv::Mat flow = uniformFlow(size, {0, 0});
    flow(after).setTo(cv::Scalar(-3, 0));  // current(p) came from previous(p - 3)
    flowMap(flow, &flow_map);
    cameraMap(cv::Matx33d::eye(), size, &camera_map);
  }
};

// The square is confirmed, the background is not.
TEST(PhotometricCheck, ConfirmsAMovedTexturedSquareAndNotTheStillBackground) {
  const MovedSquare scene;
  const cv::Mat confirmed =
      confirmation(scene.current, scene.previous, scene.flow_map, scene.camera_map);
  EXPECT_GT(cv::mean(confirmed(scene.inside))[0], 0.9);
  EXPECT_LT(cv::mean(confirmed(scene.far))[0], 0.05);
}

// A flow that bleeds from the square onto the still textured background beside it: the camera
// explains those pixels, the flow's 3 px misaligns their texture, and its motion is refuted.
TEST(PhotometricCheck, RefutesAFlowBledOntoTheStillTexturedBackground) {
  MovedSquare scene;
  const cv::Rect beside(66, 30, 20, 30);  // right of the square, still
  cv::Mat flow = uniformFlow(scene.size, {0, 0});
  flow(cv::Rect(33, 30, 53, 30)).setTo(cv::Scalar(-3, 0));  // the square's motion, and beyond
  flowMap(flow, &scene.flow_map);
  const cv::Mat confirmed =
      confirmation(scene.current, scene.previous, scene.flow_map, scene.camera_map);
  EXPECT_LT(cv::mean(confirmed(beside))[0], -0.9);
  EXPECT_GT(cv::mean(confirmed(scene.inside))[0], 0.9);
}

// The previous frame and a change of light fitted to `grey` from it, the flow exact (none).
LevelMap fittedLevels(const cv::Mat& grey, const cv::Mat& previous) {
  PhotometricCheck check;
  cv::Mat flow_map, carried;
  flowMap(uniformFlow(grey.size(), {0, 0}), &flow_map);
  check.followFlow(previous, cv::Mat(), flow_map, &carried);
  return check.fitLevels(grey);
}

// A frame brighter as a whole (an exposure, a flickering lamp): measured gain 1.2501, offset
// -10.02; the texture's brightest levels clip at 255 and are left out of the fit.
TEST(PhotometricCheck, FitsAChangeOfLight) {
  const cv::Mat previous = test::greyTexture({96, 96}, 1);
  cv::Mat brighter;
  previous.convertTo(brighter, CV_8U, 1.25, -10);
  const LevelMap levels = fittedLevels(brighter, previous);
  EXPECT_NEAR(levels.gain, 1.25, 0.005);
  EXPECT_NEAR(levels.offset, -10, 0.5);
}

// Where the light does not change, noise and a mover are no change of light: the identity.
TEST(PhotometricCheck, KeepsTheIdentityWhereTheLightStays) {
  const cv::Mat previous = test::greyTexture({96, 96}, 1);
  cv::Mat noisy(previous.size(), CV_8U);
  cv::randn(noisy, 0, 3);
  cv::Mat current;
  cv::add(previous, noisy, current, cv::noArray(), CV_8U);
  test::greyTexture({30, 30}, 2).copyTo(current(cv::Rect(33, 30, 30, 30)));
  EXPECT_TRUE(fittedLevels(current, previous).identity());
  EXPECT_TRUE(fittedLevels(previous, previous).identity());
  const cv::Mat flat(previous.size(), CV_8U, cv::Scalar(120));
  EXPECT_TRUE(fittedLevels(flat, flat).identity());
}

// The moved square, the frame 20 % brighter: with the change of light fitted
// (gain 1.18, offset 2.9: 154 at mid-grey, where 1.2 x 128 = 153.6) the square is confirmed as
// before (measured 1.00 inside, 0.00 far); without it the brightening raises the frame's median
// difference, the confirmation's unit, and the square is confirmed at 0.33.
TEST(PhotometricCheck, ConfirmsAMoverUnderAChangeOfLight) {
  MovedSquare scene;
  scene.current.convertTo(scene.current, CV_8U, 1.2);
  PhotometricCheck check;
  cv::Mat carried, with_light, without;
  check.followFlow(scene.previous, cv::Mat(), scene.flow_map, &carried);
  const LevelMap levels = check.fitLevels(scene.current);
  EXPECT_NEAR(levels.gain * 128 + levels.offset, 1.2 * 128, 2);  // mid-grey
  check.confirm(scene.current, scene.camera_map, levels, cv::Mat(), Params(), &with_light);
  check.followFlow(scene.previous, cv::Mat(), scene.flow_map, &carried);
  check.confirm(scene.current, scene.camera_map, LevelMap(), cv::Mat(), Params(), &without);
  EXPECT_GT(cv::mean(with_light(scene.inside))[0], 0.9);
  EXPECT_LT(cv::mean(with_light(scene.far))[0], 0.05);
  EXPECT_LT(cv::mean(without(scene.inside))[0], 0.6);
}

// A flat frame explains itself under any motion: a residual there, however large, is the flow
// bleeding from elsewhere, and is not confirmed.
TEST(PhotometricCheck, FlatRegionsAreNeverConfirmed) {
  const cv::Size size(64, 48);
  const cv::Mat flat(size, CV_8U, cv::Scalar(120));
  cv::Mat flow_map, camera_map;
  flowMap(uniformFlow(size, {5, -4}), &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  EXPECT_EQ(cv::countNonZero(confirmation(flat, flat, flow_map, camera_map)), 0);
}

// The confirmation as OpenCV's functions make it: the previous frame through each map by
// cv::remap, its difference to the frame by cv::absdiff, averaged by cv::blur; the margin from
// the median of the camera's. PhotometricCheck must give these values to the bit.
cv::Mat openCvConfirmation(const cv::Mat& grey, const cv::Mat& previous, const cv::Mat& flow_map,
                           const cv::Mat& camera_map, const Params& params) {
  cv::Mat errors[2];
  const cv::Mat* maps[] = {&flow_map, &camera_map};
  for (int i = 0; i < 2; ++i) {
    cv::Mat warped;
    cv::remap(previous, warped, *maps[i], cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    cv::absdiff(grey, warped, warped);
    cv::blur(warped, errors[i], cv::Size(5, 5));
  }
  // The median as the sorted middle element (index n / 2), not by the pipeline's histogram.
  std::vector<uchar> camera_errors(errors[1].begin<uchar>(), errors[1].end<uchar>());
  std::nth_element(camera_errors.begin(), camera_errors.begin() + camera_errors.size() / 2,
                   camera_errors.end());
  const int middle = camera_errors[camera_errors.size() / 2];
  const float margin =
      static_cast<float>(params.photometric_margin) * static_cast<float>(std::max(middle, 1));
  cv::Mat confirmation(grey.size(), CV_32F);
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      const int better = errors[1].at<uchar>(y, x) - errors[0].at<uchar>(y, x);
      confirmation.at<float>(y, x) = std::clamp(static_cast<float>(better) / margin, -1.f, 1.f);
    }
  }
  return confirmation;
}

// The confirmation and the carried mask against OpenCV's, bit for bit, and not trivially (some
// pixels confirmed in part); the confirmation the same without a mask, when nothing is carried.
void expectOpenCvsResults(const cv::Mat& grey, const cv::Mat& previous, const cv::Mat& mask,
                          const cv::Mat& flow_map, const cv::Mat& camera_map,
                          const std::string& what, PhotometricCheck* check) {
  cv::Mat carried, ours;
  check->followFlow(previous, mask, flow_map, &carried);
  check->confirm(grey, camera_map, LevelMap(), cv::Mat(), Params(), &ours);
  const cv::Mat opencv = openCvConfirmation(grey, previous, flow_map, camera_map, Params());
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  ASSERT_EQ(ours.type(), CV_32F) << what;
  EXPECT_EQ(cv::countNonZero(ours != opencv), 0) << what;
  if (grey.total() >= 100) {
    EXPECT_GT(cv::countNonZero((ours > 0) & (ours < 1)), 0) << what << ": nothing confirmed in part";
    EXPECT_GT(cv::countNonZero((ours < 0) & (ours > -1)), 0) << what << ": nothing refuted in part";
  }
  cv::Mat opencv_carried;
  cv::remap(mask, opencv_carried, flow_map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  ASSERT_EQ(carried.size(), opencv_carried.size()) << what;
  ASSERT_EQ(carried.type(), CV_8U) << what;
  EXPECT_EQ(cv::countNonZero(carried != opencv_carried), 0) << what;

  check->followFlow(previous, cv::Mat(), flow_map, &carried);
  check->confirm(grey, camera_map, LevelMap(), cv::Mat(), Params(), &ours);
  EXPECT_TRUE(carried.empty()) << what;
  EXPECT_EQ(cv::countNonZero(ours != opencv), 0) << what << " without a mask";
}

cv::Mat randomFlow(cv::Size size, float reach, uint64 seed) {
  cv::Mat flow(size, CV_32FC2);
  cv::RNG(seed).fill(flow, cv::RNG::UNIFORM, cv::Scalar::all(-reach), cv::Scalar::all(reach));
  cv::GaussianBlur(flow, flow, {0, 0}, 2);  // smooth, as a flow; still leaving the frame
  return flow;
}

// A moved texture, random flows around the truth (some leaving the frame), a camera that zooms
// and turns a little: the confirmation and the carried mask are OpenCV's, at sizes down to a
// pixel (the pipeline gives the check frames of 16 pixels a side and more).
TEST(PhotometricCheck, GivesOpenCvsConfirmationAndCarriedMask) {
  const cv::Size sizes[] = {{96, 72}, {320, 240}, {33, 17}, {16, 16}, {7, 100}, {5, 5},
                            {2, 2},   {1, 1}};
  for (const cv::Size size : sizes) {
    const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height);
    const cv::Mat previous = test::greyTexture(size, 21);
    cv::Mat grey;
    cv::warpAffine(previous, grey, cv::Matx23d(1, 0, 1.3, 0, 1, -0.6), size, cv::INTER_LINEAR,
                   cv::BORDER_REFLECT);
    grey(cv::Rect(0, 0, (size.width + 1) / 2, (size.height + 1) / 2)) += 9;  // changes no map explains
    cv::Mat mask = test::greyTexture(size, 22) > 128;
    for (const float reach : {1.5f, 12.f}) {
      const cv::Mat truth(size, CV_32FC2, cv::Scalar(1.3, -0.6));
      cv::Mat flow_map, camera_map;
      flowMap(truth + randomFlow(size, reach, 23), &flow_map);
      cameraMap(cv::Matx33d(1.02, -0.03, 1.1, 0.03, 1.01, -0.4, 0, 0, 1), size, &camera_map);
      PhotometricCheck check;
      expectOpenCvsResults(grey, previous, mask, flow_map, camera_map,
                           what + " reach " + std::to_string(reach), &check);
    }
  }
}

// Another margin changes the division, not the agreement; an identity camera (a still camera's
// fit, or its fallback) too.
TEST(PhotometricCheck, GivesOpenCvsConfirmationWithOtherMarginsAndAStillCamera) {
  const cv::Size size(80, 60);
  const cv::Mat previous = test::greyTexture(size, 31);
  const cv::Mat grey = test::greyTexture(size, 32);
  cv::Mat flow_map, camera_map;
  flowMap(randomFlow(size, 4.f, 33), &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  for (const double margin : {0.01, 0.37, 1.0, 3.0, 100.0}) {
    Params params;
    params.photometric_margin = margin;
    EXPECT_EQ(cv::countNonZero(confirmation(grey, previous, flow_map, camera_map, params) !=
                               openCvConfirmation(grey, previous, flow_map, camera_map, params)),
              0)
        << "margin " << margin;
  }
}

// DAVIS frames at the working size, their flow as DenseFlow finds it, the camera a homography
// near the pair's motion, the previous frame's mask a thresholded frame; one check object over
// the pairs, as the pipeline keeps it.
TEST(PhotometricCheck, GivesOpenCvsConfirmationAndCarriedMaskOnDavisPairs) {
  const std::vector<std::string> files = test::davisFrames("dog", 5);
  if (files.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  DenseFlow dense(Params().flow_finest_scale);
  PhotometricCheck check;
  cv::Mat previous, flows[2], flow_map, camera_map;  // two flows in flight, as DenseFlow asks
  cameraMap(cv::Matx33d(1.01, 0.01, -2.5, -0.01, 1.01, 0.8, 1e-5, -2e-5, 1), {320, 240},
            &camera_map);
  for (size_t t = 0; t < files.size(); ++t) {
    cv::Mat grey = cv::imread(files[t], cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(grey.empty()) << files[t];
    cv::resize(grey, grey, {320, 240}, 0, 0, cv::INTER_AREA);
    dense.next(grey, &flows[t % 2]);
    if (!flows[t % 2].empty()) {
      flowMap(flows[t % 2], &flow_map);
      expectOpenCvsResults(grey, previous, previous > 100, flow_map, camera_map, files[t], &check);
    }
    previous = grey;
  }
}

TEST(MotionEvidence, ConfirmationScalesOnlyEvidenceForMotion) {
  cv::Mat evidence = (cv::Mat_<float>(1, 6) << 2.f, -1.f, 1.f, 1.f, 2.5f, -1.f);
  const cv::Mat confirmation = (cv::Mat_<float>(1, 6) << 0.5f, 0.f, 0.f, -0.5f, -1.f, -1.f);
  Params params;  // evidence_min -2
  confirmMotion(confirmation, params, &evidence);
  EXPECT_FLOAT_EQ(evidence.at<float>(0), 1.f);
  EXPECT_FLOAT_EQ(evidence.at<float>(1), -1.f);  // background evidence needs no confirmation
  EXPECT_FLOAT_EQ(evidence.at<float>(2), 0.f);   // neither explains better: nothing said
  EXPECT_FLOAT_EQ(evidence.at<float>(3), -0.5f);  // refuted in part: static in part
  EXPECT_FLOAT_EQ(evidence.at<float>(4), -2.f);   // refuted: static, at most as a pair can say
  EXPECT_FLOAT_EQ(evidence.at<float>(5), -1.f);   // nor is background evidence made stronger
}

TEST(MotionEvidence, ScaleIsTheUpperQuantileWithAFloorAtFiveMedians) {
  Params params;
  std::vector<float> residuals(100, 0.2f);
  for (int i = 90; i < 100; ++i) residuals[static_cast<size_t>(i)] = 3.f;
  EXPECT_FLOAT_EQ(residualScale(&residuals, params), 3.f);  // the 95th percentile
  params.evidence_quantile = 0.5;
  EXPECT_FLOAT_EQ(residualScale(&residuals, params), 1.f);  // 5 x the median 0.2
  std::vector<float> still = {0.f, 0.f};
  EXPECT_FLOAT_EQ(residualScale(&still, params), 0.1f);  // what the flow resolves
}

TEST(MotionEvidence, TheCarriedMaskFollowsTheFlow) {
  cv::Mat mask(40, 40, CV_8U, cv::Scalar(0));
  mask(cv::Rect(10, 10, 8, 8)).setTo(255);
  cv::Mat flow_map;
  flowMap(uniformFlow(mask.size(), {-4, -2}), &flow_map);  // moved by (+4, +2)
  const cv::Mat carried = carriedMask(mask, flow_map);
  EXPECT_EQ(cv::countNonZero(carried(cv::Rect(14, 12, 8, 8)) == 255), 64);
  EXPECT_EQ(cv::countNonZero(carried), 64);
}

// A mover at columns 30-59 of the previous frame moved 3 px right, the camera still. DIS gives
// the mover's flow also to the 8 columns behind it (25-32 now): of those, 30-32 were hidden by
// the mover and are uncovered — the flow leads them out of the previous mask — while 25-29
// were seen and stay as they are, as does the mover itself (its flow leads into the mask).
TEST(MotionEvidence, PositiveEvidenceIsDroppedWhereTheMoverUncoveredTheBackground) {
  const cv::Size size(80, 20);
  cv::Mat previous_mask(size, CV_8U, cv::Scalar(0));
  previous_mask.colRange(30, 60).setTo(255);
  cv::Mat flow = uniformFlow(size, {0, 0});
  flow.colRange(25, 63).setTo(cv::Scalar(-3, 0));  // the mover, now 33-62, and its smear
  cv::Mat flow_map, camera_map;
  flowMap(flow, &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  const cv::Mat carried = carriedMask(previous_mask, flow_map);
  cv::Mat evidence(size, CV_32F, cv::Scalar(2));
  evidence.at<float>(5, 31) = -1;
  dropUncovered(carried, previous_mask, camera_map, &evidence);

  cv::Mat uncovered;
  uncoveredPixels(carried, previous_mask, camera_map, &uncovered);
  EXPECT_EQ(cv::countNonZero(uncovered), 3 * size.height);
  EXPECT_EQ(cv::countNonZero(uncovered.colRange(30, 33)), 3 * size.height);
  EXPECT_EQ(cv::countNonZero(evidence.colRange(30, 33)), 1);  // zero but the negative one
  EXPECT_FLOAT_EQ(evidence.at<float>(5, 31), -1.f);
  EXPECT_EQ(cv::countNonZero(evidence.colRange(0, 30) != 2), 0);
  EXPECT_EQ(cv::countNonZero(evidence.colRange(33, 80) != 2), 0);
}

}  // namespace
}  // namespace movseg
