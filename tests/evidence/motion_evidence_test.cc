#include "evidence/motion_evidence.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "flow/flow_camera.h"
#include "test_support.h"

namespace movseg {
namespace {

cv::Mat uniformFlow(cv::Size size, cv::Vec2f motion) {
  return cv::Mat(size, CV_32FC2, cv::Scalar(motion[0], motion[1]));
}

// A textured square moved 3 px right over a still textured background, the flow exact: the
// square is confirmed, the background is not.
TEST(PhotometricCheck, ConfirmsAMovedTexturedSquareAndNotTheStillBackground) {
  const cv::Size size(96, 96);
  const cv::Mat background = test::greyTexture(size, 1);
  const cv::Mat object = test::greyTexture(size, 2);
  const cv::Rect before(30, 30, 30, 30), after(33, 30, 30, 30);
  cv::Mat previous = background.clone(), current = background.clone();
  object(before).copyTo(previous(before));
  object(before).copyTo(current(after));
  cv::Mat flow = uniformFlow(size, {0, 0});
  flow(after).setTo(cv::Scalar(-3, 0));  // current(p) came from previous(p - 3)

  cv::Mat flow_map, camera_map, confirmation;
  flowMap(flow, &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  PhotometricCheck check;
  check.confirm(current, previous, flow_map, camera_map, Params(), &confirmation);

  const cv::Rect inside(38, 36, 18, 18), far(0, 70, 96, 26);
  EXPECT_GT(cv::mean(confirmation(inside))[0], 0.9);
  EXPECT_LT(cv::mean(confirmation(far))[0], 0.05);
}

// A flat frame explains itself under any motion: a residual there, however large, is the flow
// bleeding from elsewhere, and is not confirmed.
TEST(PhotometricCheck, FlatRegionsAreNeverConfirmed) {
  const cv::Size size(64, 48);
  const cv::Mat flat(size, CV_8U, cv::Scalar(120));
  cv::Mat flow_map, camera_map, confirmation;
  flowMap(uniformFlow(size, {5, -4}), &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  PhotometricCheck check;
  check.confirm(flat, flat, flow_map, camera_map, Params(), &confirmation);
  EXPECT_EQ(cv::countNonZero(confirmation), 0);
}

TEST(MotionEvidence, ConfirmationScalesOnlyEvidenceForMotion) {
  cv::Mat evidence = (cv::Mat_<float>(1, 3) << 2.f, -1.f, 1.f);
  const cv::Mat confirmation = (cv::Mat_<float>(1, 3) << 0.5f, 0.f, 0.f);
  confirmMotion(confirmation, &evidence);
  EXPECT_FLOAT_EQ(evidence.at<float>(0), 1.f);
  EXPECT_FLOAT_EQ(evidence.at<float>(1), -1.f);  // background evidence needs no confirmation
  EXPECT_FLOAT_EQ(evidence.at<float>(2), 0.f);
}

TEST(MotionEvidence, ScaleIsTheUpperQuantileWithAFloorAtFiveMedians) {
  Params params;
  std::vector<float> residuals(100, 0.2f);
  for (int i = 90; i < 100; ++i) residuals[static_cast<size_t>(i)] = 3.f;
  EXPECT_FLOAT_EQ(residualScale(residuals, params), 3.f);  // the 95th percentile
  params.evidence_quantile = 0.5;
  EXPECT_FLOAT_EQ(residualScale(residuals, params), 1.f);  // 5 x the median 0.2
  EXPECT_FLOAT_EQ(residualScale({0.f, 0.f}, params), 0.1f);  // what the flow resolves
}

TEST(MotionEvidence, TheCarriedMaskFollowsTheFlow) {
  cv::Mat mask(40, 40, CV_8U, cv::Scalar(0));
  mask(cv::Rect(10, 10, 8, 8)).setTo(255);
  cv::Mat flow_map, carried;
  flowMap(uniformFlow(mask.size(), {-4, -2}), &flow_map);  // moved by (+4, +2)
  carryMask(mask, flow_map, &carried);
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
  cv::Mat flow_map, camera_map, carried;
  flowMap(flow, &flow_map);
  cameraMap(cv::Matx33d::eye(), size, &camera_map);
  carryMask(previous_mask, flow_map, &carried);
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
