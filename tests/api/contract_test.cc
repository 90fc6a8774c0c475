// What every method promises (movseg/segmenter.h), whichever pipeline Params::method chooses:
// a 0/255 mask of the frame's size for any supported frame, an empty first frame, a restart on
// a size change or reset, bit-identical masks for equal input, clear errors for bad frames.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "eval/metrics.h"
#include "movseg/background_subtractor.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

class Contract : public ::testing::TestWithParam<Method> {
 protected:
  Params params() const {
    Params p;
    p.method = GetParam();
    return p;
  }
  std::vector<cv::Mat> masksOf(const std::vector<cv::Mat>& frames) const {
    return test::masksOf(frames, params());
  }
};

TEST_P(Contract, FirstFrameIsEmptyAndEveryMaskIsBinaryOfTheFrameSize) {
  Segmenter segmenter(params());
  const std::vector<cv::Mat> frames = test::synthFrames(6, 1);
  for (size_t t = 0; t < frames.size(); ++t) {
    const Result r = segmenter.process(frames[t]);
    test::expectValidResult(r, frames[t].size());
    EXPECT_EQ(r.diagnostics.first_frame, t == 0) << t;
    if (t == 0) {
      EXPECT_EQ(cv::countNonZero(r.mask), 0);
    }
  }
}

// BGRA, 16-bit and float frames in [0, 1] carry the BGR frames' picture, so they give their
// masks exactly; a grey frame gives the masks of its grey picture in three channels.
TEST_P(Contract, AcceptsGreyBgra16BitAndFloatFrames) {
  const std::vector<cv::Mat> bgr = test::synthFrames(4, 2);
  std::vector<cv::Mat> bgra, deep, real, grey, grey_bgr;
  for (const cv::Mat& f : bgr) {
    cv::Mat converted;
    cv::cvtColor(f, converted, cv::COLOR_BGR2BGRA);
    bgra.push_back(converted);
    f.convertTo(converted, CV_16UC3, 256);
    deep.push_back(converted);
    f.convertTo(converted, CV_32FC3, 1.0 / 255);
    real.push_back(converted);
    cv::cvtColor(f, converted, cv::COLOR_BGR2GRAY);
    grey.push_back(converted);
    cv::cvtColor(converted, converted, cv::COLOR_GRAY2BGR);
    grey_bgr.push_back(converted);
  }
  const std::vector<cv::Mat> expected = masksOf(bgr);
  ASSERT_GT(cv::countNonZero(expected.back()), 0);  // equal empty masks would prove nothing
  EXPECT_TRUE(test::identical(masksOf(bgra), expected));
  EXPECT_TRUE(test::identical(masksOf(deep), expected));
  EXPECT_TRUE(test::identical(masksOf(real), expected));
  const std::vector<cv::Mat> expected_grey = masksOf(grey_bgr);
  EXPECT_GT(cv::countNonZero(expected_grey.back()), 0);
  EXPECT_TRUE(test::identical(masksOf(grey), expected_grey));
}

// A cv::Mat of 3 dimensions is no frame and no region (a region of them made every later
// frame fail).
TEST_P(Contract, RejectsEmptyFramesAndUnsupportedChannelCounts) {
  Segmenter segmenter(params());
  EXPECT_THROW(segmenter.process(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(segmenter.process(cv::Mat(8, 8, CV_8UC2, cv::Scalar(1, 2))), std::invalid_argument);
  const int sides[] = {8, 8, 3};
  const cv::Mat cube(3, sides, CV_8UC1, cv::Scalar(1));
  EXPECT_THROW(segmenter.process(cube), std::invalid_argument);
  EXPECT_THROW(segmenter.setIgnoredRegion(cube), std::invalid_argument);
  test::expectValidResult(segmenter.process(test::synthFrames(1, 1)[0]), {320, 240});
  Params bad = params();
  bad.gmm_clusters = 0;
  EXPECT_THROW(Segmenter{bad}, std::invalid_argument);
  EXPECT_THROW(createMovingCameraSubtractor(bad), std::invalid_argument);
}

TEST_P(Contract, SizeChangeRestartsTheStream) {
  const std::vector<cv::Mat> frames = test::synthFrames(3, 3);
  Segmenter segmenter(params());
  segmenter.process(frames[0]);
  segmenter.process(frames[1]);
  cv::Mat smaller;
  cv::resize(frames[2], smaller, {160, 120});
  const Result r = segmenter.process(smaller);
  test::expectValidResult(r, smaller.size());
  EXPECT_TRUE(r.diagnostics.reset);
  EXPECT_TRUE(r.diagnostics.first_frame);
  EXPECT_EQ(cv::countNonZero(r.mask), 0);
}

// reset() and the subtractor's clear() forget the stream: the next frame is a first frame.
TEST_P(Contract, ResetAndClearMakeTheNextFrameAFirstFrame) {
  const std::vector<cv::Mat> frames = test::synthFrames(3, 4);
  Segmenter segmenter(params());
  const cv::Ptr<cv::BackgroundSubtractor> subtractor = createMovingCameraSubtractor(params());
  cv::Mat mask;
  for (int t = 0; t < 2; ++t) {
    segmenter.process(frames[t]);
    subtractor->apply(frames[t], mask);
  }
  segmenter.reset();
  subtractor->clear();
  EXPECT_TRUE(segmenter.compensatedPreviousFrame().empty());
  cv::Mat background;
  subtractor->getBackgroundImage(background);
  EXPECT_TRUE(background.empty());
  const Result r = segmenter.process(frames[2]);
  EXPECT_TRUE(r.diagnostics.first_frame);
  EXPECT_FALSE(r.diagnostics.reset);
  EXPECT_EQ(cv::countNonZero(r.mask), 0);
  subtractor->apply(frames[2], mask);
  EXPECT_EQ(cv::countNonZero(mask), 0);
}

// Tiny frames also say that their camera could not be measured, by every method that measures
// one; MOG2, which measures none, says nothing.
TEST_P(Contract, TinyFlatAndNoisyFramesGiveValidMasks) {
  const bool measures_camera = GetParam() != Method::kMog2;
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(2, 2), cv::Size(7, 1000), cv::Size(1000, 7),
                              cv::Size(17, 17)}) {
    Segmenter segmenter(params());
    const cv::Mat a = test::texture(size, 1), b = test::texture(size, 2);
    for (const cv::Mat& frame : {a, b, a}) {
      const Result r = segmenter.process(frame);
      test::expectValidResult(r, size);
      if (r.diagnostics.first_frame || size.area() == 17 * 17) continue;
      EXPECT_EQ(r.diagnostics.motion_fallback, measures_camera) << size;
    }
  }
  Segmenter segmenter(params());
  for (int i = 0; i < 3; ++i) {
    cv::Mat noise(240, 320, CV_8UC3);
    cv::RNG(i + 1).fill(noise, cv::RNG::UNIFORM, 0, 256);
    test::expectValidResult(segmenter.process(noise), noise.size());
    const cv::Mat flat(240, 320, CV_8UC3, cv::Scalar::all(40 * i));
    test::expectValidResult(segmenter.process(flat), flat.size());
  }
}

// Equal input gives equal masks, and a caller refilling one buffer (cap >> frame) changes
// nothing: the segmenter keeps its own copy of the frames it needs.
TEST_P(Contract, SameInputGivesBitIdenticalMasksWhateverTheBuffer) {
  const std::vector<cv::Mat> frames = test::synthFrames(8, 5);
  const std::vector<cv::Mat> expected = masksOf(frames);
  ASSERT_GT(cv::countNonZero(expected.back()), 0);  // equal empty masks would prove nothing
  EXPECT_TRUE(test::identical(masksOf(frames), expected));
  Segmenter segmenter(params());
  cv::Mat buffer;
  std::vector<cv::Mat> reused;
  for (const cv::Mat& frame : frames) {
    frame.copyTo(buffer);
    reused.push_back(segmenter.process(buffer).mask);
  }
  EXPECT_TRUE(test::identical(reused, expected));
}

// The region to ignore is given at half the frames' size and scaled to them: no mask has a
// pixel in it, where without it the movers show. An empty region, and a reset, give back the
// masks without one.
TEST_P(Contract, AnIgnoredRegionNeverMovesAtAnySize) {
  const std::vector<cv::Mat> frames = test::synthFrames(8, 5);
  const cv::Size size = frames[0].size();
  const cv::Rect left(0, 0, size.width / 2, size.height);
  const std::vector<cv::Mat> expected = masksOf(frames);
  int shown = 0;
  for (const cv::Mat& mask : expected) shown += cv::countNonZero(mask(left));
  ASSERT_GT(shown, 0);  // a region where nothing moves would prove nothing
  cv::Mat region = cv::Mat::zeros(size / 2, CV_8U);
  region(cv::Rect(0, 0, size.width / 4, size.height / 2)).setTo(1);
  Segmenter segmenter(params());
  segmenter.setIgnoredRegion(region);
  for (const cv::Mat& frame : frames) {
    const Result r = segmenter.process(frame);
    test::expectValidResult(r, size);
    EXPECT_EQ(cv::countNonZero(r.mask(left)), 0);
  }
  segmenter.setIgnoredRegion(cv::Mat());
  segmenter.reset();
  std::vector<cv::Mat> again;
  for (const cv::Mat& frame : frames) again.push_back(segmenter.process(frame).mask);
  EXPECT_TRUE(test::identical(again, expected));
}

// A region cleared in mid-stream, without reset(), ignores nothing from the next frame on: the
// movers it hid are in the mask again within two frames, as where it was never set.
TEST_P(Contract, AnIgnoredRegionClearedInMidStreamLetsTheMoversBack) {
  const std::vector<cv::Mat> frames = test::synthFrames(12, 5);
  const cv::Size size = frames[0].size();
  const cv::Rect left(0, 0, size.width / 2, size.height);
  const std::vector<cv::Mat> expected = masksOf(frames);
  cv::Mat region = cv::Mat::zeros(size, CV_8U);
  region(left).setTo(255);
  Segmenter segmenter(params());
  segmenter.setIgnoredRegion(region);
  const size_t cleared = 6;
  for (size_t t = 0; t < cleared; ++t) {
    EXPECT_EQ(cv::countNonZero(segmenter.process(frames[t]).mask(left)), 0) << t;
  }
  segmenter.setIgnoredRegion(cv::Mat());
  for (size_t t = cleared; t < frames.size(); ++t) {
    const cv::Mat mask = segmenter.process(frames[t]).mask;
    if (t < cleared + 2) continue;
    const int shown = cv::countNonZero(expected[t](left));
    ASSERT_GT(shown, 0) << t;  // nothing to show would prove nothing
    EXPECT_GT(scoreFrame(mask(left), expected[t](left)).j, 0.8) << t;
  }
}

TEST_P(Contract, RefusesAnIgnoredRegionOfAnotherType) {
  Segmenter segmenter(params());
  EXPECT_THROW(segmenter.setIgnoredRegion(cv::Mat::zeros(24, 32, CV_8UC3)), std::invalid_argument);
  EXPECT_THROW(segmenter.setIgnoredRegion(cv::Mat::ones(24, 32, CV_32F)), std::invalid_argument);
  const std::vector<cv::Mat> frames = test::synthFrames(4, 5);
  std::vector<cv::Mat> masks;
  for (const cv::Mat& frame : frames) masks.push_back(segmenter.process(frame).mask);
  // Equal empty masks would prove nothing.
  ASSERT_GT(cv::countNonZero(masks.back()), 0);
  EXPECT_TRUE(test::identical(masks, masksOf(frames)));  // nothing was set
}

std::vector<Method> everyMethod() {
  std::vector<Method> methods;
  for (size_t m = 0; m < enumNames<Method>().size(); ++m) methods.push_back(static_cast<Method>(m));
  return methods;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Contract, ::testing::ValuesIn(everyMethod()),
                         [](const ::testing::TestParamInfo<Method>& param_info) {
                           std::string name = enumNames<Method>()[static_cast<size_t>(param_info.param)];
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace movseg
