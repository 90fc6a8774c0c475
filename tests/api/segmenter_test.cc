// The paper's pipeline through the public API: it finds the object, reports the camera model,
// skips alignment for a static camera and draws each stage's pictures. What every method
// promises is in contract_test.cc.
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "motion/motion_fixture.h"
#include "movseg/segmenter.h"
#include "test_support.h"

namespace movseg {
namespace {

double iou(const cv::Mat& a, const cv::Mat& b) {
  const double inter = cv::countNonZero(a & b), uni = cv::countNonZero(a | b);
  return uni > 0 ? inter / uni : 1.0;
}

void expectBinaryMaskOfSize(const Result& r, cv::Size size) {
  ASSERT_EQ(r.mask.type(), CV_8U);
  ASSERT_EQ(r.mask.size(), size);
  EXPECT_EQ(cv::countNonZero((r.mask != 0) & (r.mask != 255)), 0);
}

test::FramePair movingPair() {
  test::PairSpec spec;
  spec.camera = test::similarityAboutCentre(spec.size, 1.5, 1.01, {3, -2});
  spec.object_fraction = 0.15;
  return test::makePair(spec);
}

// The paper's pipeline, whose seeds, matches and stage pictures these tests read.
Params paper() { return test::withMethod(Method::kPaper); }

TEST(Segmenter, FirstFrameIsEmptyThenTheObjectIsFound) {
  const test::FramePair pair = movingPair();
  Segmenter segmenter(paper());
  const Result first = segmenter.process(pair.prev);
  expectBinaryMaskOfSize(first, pair.prev.size());
  EXPECT_TRUE(first.diagnostics.first_frame);
  EXPECT_EQ(cv::countNonZero(first.mask), 0);

  const Result second = segmenter.process(pair.cur);
  expectBinaryMaskOfSize(second, pair.cur.size());
  EXPECT_FALSE(second.diagnostics.first_frame);
  EXPECT_GT(iou(second.mask, pair.cur_mask), 0.85);
  EXPECT_GT(second.diagnostics.foreground_seeds, 5);
  EXPECT_GT(second.diagnostics.background_seeds, 50);
  EXPECT_GT(second.diagnostics.matches, 50);
  EXPECT_GT(second.diagnostics.total_ms, 0.0);
  EXPECT_FALSE(second.features.empty());
}

TEST(Segmenter, ReportsTheCameraModelInFullResolutionPixels) {
  test::PairSpec spec;
  spec.size = {640, 480};
  spec.camera = test::similarityAboutCentre(spec.size, 1, 1.0, {8, -4});
  spec.object_fraction = 0.1;
  const test::FramePair pair = test::makePair(spec);
  Segmenter segmenter(paper());
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  EXPECT_TRUE(r.diagnostics.model_is_affine);
  EXPECT_LT(test::cornerError(r.diagnostics.model, spec.camera, spec.size), 1.0);
}

TEST(Segmenter, StaticCameraModeSkipsAlignment) {
  test::PairSpec spec;
  spec.object_fraction = 0.15;
  const test::FramePair pair = test::makePair(spec);  // identity camera
  Params params = paper();
  params.static_camera = true;
  Segmenter segmenter(params);
  segmenter.process(pair.prev);
  const Result r = segmenter.process(pair.cur);
  EXPECT_EQ(r.diagnostics.model, cv::Matx33d::eye());
  EXPECT_EQ(r.diagnostics.matches, 0);
  EXPECT_GT(iou(r.mask, pair.cur_mask), 0.85);
}

TEST(Segmenter, DebugPicturesWhenAsked) {
  const test::FramePair pair = movingPair();
  for (const bool asked : {true, false}) {
    Params params = paper();
    params.debug_images = asked;
    Segmenter segmenter(params);
    segmenter.process(pair.prev);
    const Result r = segmenter.process(pair.cur);
    EXPECT_FALSE(segmenter.compensatedPreviousFrame().empty());
    if (!asked) {
      EXPECT_TRUE(r.debug.empty()) << r.debug.begin()->first;
      continue;
    }
    for (const char* name :
         {"matches", "difference", "features", "features_refined", "confidence", "mask"}) {
      ASSERT_TRUE(r.debug.count(name)) << name;
      EXPECT_FALSE(r.debug.at(name).empty()) << name;
    }
  }
}

// OpenCV's warps take less than 32767 pixels a side; a frame that would exceed it at a working
// scale is refused up front, as invalid_argument, and the stream goes on.
TEST(Segmenter, FramesBeyondTheWarpsLimitAreRefusedUpFront) {
  Params native;
  native.alignment_width = 0;
  native.segmentation_width = 0;
  Segmenter segmenter(native);
  const cv::Mat ordinary(48, 64, CV_8UC3, cv::Scalar(90, 120, 150));
  segmenter.process(ordinary);
  EXPECT_THROW(segmenter.process(cv::Mat(40000, 10, CV_8U, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(segmenter.process(cv::Mat(10, 40000, CV_8U, cv::Scalar(0))), std::invalid_argument);
  EXPECT_FALSE(segmenter.process(ordinary).diagnostics.first_frame);  // the stream went on

  // Scaled down to 320 on their longer side, the same frames are fine, wide or tall.
  EXPECT_EQ(Segmenter().process(cv::Mat(10, 40000, CV_8U, cv::Scalar(0))).mask.size(),
            cv::Size(40000, 10));
  EXPECT_EQ(Segmenter().process(cv::Mat(40000, 10, CV_8U, cv::Scalar(0))).mask.size(),
            cv::Size(10, 40000));
}

// Whatever OpenCV throws leaves as std::runtime_error with its one-line reason: here the warp
// of a 40000-wide previous frame at full resolution.
TEST(Segmenter, OpenCvFailuresBecomeRuntimeErrors) {
  Segmenter segmenter(paper());  // it warps the full-resolution frame
  const cv::Mat wide(8, 40000, CV_8UC3, cv::Scalar(10, 20, 30));
  segmenter.process(wide);
  segmenter.process(wide);
  try {
    segmenter.compensatedPreviousFrame();
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("OpenCV failed"), std::string::npos) << e.what();
  }
}

// A frame too large for the memory left is a one-line std::runtime_error, not a std::bad_alloc or
// a crash, and the segmenter goes on with the next frame that fits. The address space is limited
// for the call alone (not under AddressSanitizer, whose shadow memory needs terabytes of it).
TEST(Segmenter, AFailedAllocationBecomesARuntimeError) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit leaves";
#else
  const cv::Mat huge(12000, 12000, CV_8U, cv::Scalar(0));  // its colour copy takes 432 MB
  Segmenter segmenter;
  long pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &saved), 0);
  rlimit limited = saved;
  limited.rlim_cur = static_cast<rlim_t>(pages) * sysconf(_SC_PAGESIZE) + (256 << 20);
  ASSERT_EQ(setrlimit(RLIMIT_AS, &limited), 0);
  std::string error;
  try {
    segmenter.process(huge);
  } catch (const std::runtime_error& e) {
    error = e.what();
  } catch (...) {
    error = "another exception";
  }
  ASSERT_EQ(setrlimit(RLIMIT_AS, &saved), 0);
  EXPECT_NE(error.find("allocate"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  const test::FramePair pair = movingPair();
  segmenter.process(pair.prev);
  EXPECT_GT(iou(segmenter.process(pair.cur).mask, pair.cur_mask), 0.5);
#endif
}

// Float frames are read as [0, 1]; one in 0-255 would saturate to white and give an empty mask
// in silence, so it is refused with a message that says what to pass instead.
TEST(Segmenter, RejectsFloatFramesOutsideTheUnitRange) {
  const test::FramePair pair = movingPair();
  cv::Mat unit, byte_range, negative;
  pair.cur.convertTo(unit, CV_32FC3, 1.0 / 255);
  pair.cur.convertTo(byte_range, CV_32FC3);
  unit.convertTo(negative, CV_64FC3, 1.0, -0.5);
  Segmenter segmenter;
  EXPECT_NO_THROW(segmenter.process(unit));
  for (const cv::Mat& frame : {byte_range, negative}) {
    try {
      segmenter.process(frame);
      ADD_FAILURE() << "accepted a float frame outside [0, 1]";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("float frame values must be in [0, 1]"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace movseg
