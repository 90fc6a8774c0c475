// StreamSegmenter: a frame's analysis overlapped with the previous frame's segmentation gives
// Segmenter::process's masks bit for bit, one push later, for every method.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "movseg/stream_segmenter.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

struct Case {
  Method method;
  int threads;
};

class Stream : public ::testing::TestWithParam<Case> {
 protected:
  Params params() const {
    Params p;
    p.method = GetParam().method;
    return p;
  }
};

// Pushes every frame, then flushes; returns the masks in frame order.
std::vector<cv::Mat> streamed(StreamSegmenter& stream, const std::vector<cv::Mat>& frames) {
  std::vector<cv::Mat> masks;
  for (size_t t = 0; t < frames.size(); ++t) {
    const std::optional<Result> previous = stream.push(frames[t]);
    EXPECT_EQ(previous.has_value(), t > 0) << t;
    if (previous) masks.push_back(previous->mask);
  }
  std::optional<Result> last = stream.flush();
  EXPECT_TRUE(last.has_value());
  if (last) masks.push_back(last->mask);
  EXPECT_FALSE(stream.flush().has_value());
  return masks;
}

TEST_P(Stream, GivesTheSegmentersMasksOnePushLater) {
  const std::vector<cv::Mat> frames = test::synthFrames(10, 6);
  StreamSegmenter stream(params(), GetParam().threads);
  const std::vector<cv::Mat> masks = streamed(stream, frames);
  const std::vector<cv::Mat> expected = test::masksOf(frames, params());
  ASSERT_GT(cv::countNonZero(expected.back()), 0);  // equal empty masks would prove nothing
  EXPECT_TRUE(test::identical(masks, expected));
}

// The region to ignore, set between pushes, counts from the next frame pushed on, as for
// Segmenter; the frame pushed before it (being analysed on two threads) keeps none.
TEST_P(Stream, AnIgnoredRegionGivesTheSegmentersMasks) {
  const std::vector<cv::Mat> frames = test::synthFrames(8, 5);
  cv::Mat region = cv::Mat::zeros(frames[0].size(), CV_8U);
  region(cv::Rect(0, 0, region.cols / 2, region.rows)).setTo(255);
  Segmenter segmenter(params());
  StreamSegmenter stream(params(), GetParam().threads);
  std::vector<cv::Mat> expected, masks;
  for (size_t t = 0; t < frames.size(); ++t) {
    if (t == 3) {
      segmenter.setIgnoredRegion(region);
      stream.setIgnoredRegion(region);
    }
    expected.push_back(segmenter.process(frames[t]).mask);
    if (std::optional<Result> previous = stream.push(frames[t])) masks.push_back(previous->mask);
  }
  if (std::optional<Result> last = stream.flush()) masks.push_back(last->mask);
  ASSERT_GT(cv::countNonZero(expected.back()), 0);  // equal empty masks would prove nothing
  EXPECT_TRUE(test::identical(masks, expected));
}

// Each frame's mask at once, as `movseg segment` takes them on one thread: the jobs still take
// turns (a pipeline may keep references into the previous frame's analysis).
TEST_P(Stream, FlushingAfterEveryPushGivesTheSegmentersMasks) {
  const std::vector<cv::Mat> frames = test::synthFrames(6, 6);
  StreamSegmenter stream(params(), GetParam().threads);
  std::vector<cv::Mat> masks;
  for (const cv::Mat& frame : frames) {
    EXPECT_FALSE(stream.push(frame).has_value());
    masks.push_back(stream.flush()->mask);
  }
  const std::vector<cv::Mat> expected = test::masksOf(frames, params());
  ASSERT_GT(cv::countNonZero(expected.back()), 0);
  EXPECT_TRUE(test::identical(masks, expected));
}

TEST_P(Stream, RestartsOnASizeChangeAndAfterReset) {
  std::vector<cv::Mat> frames = test::synthFrames(6, 7);
  for (size_t t = 3; t < frames.size(); ++t) cv::resize(frames[t], frames[t], {160, 120});
  StreamSegmenter stream(params(), GetParam().threads);
  std::vector<Result> results;
  for (const cv::Mat& frame : frames) {
    if (std::optional<Result> r = stream.push(frame)) results.push_back(std::move(*r));
  }
  results.push_back(*stream.flush());
  ASSERT_EQ(results.size(), frames.size());
  for (size_t t = 0; t < frames.size(); ++t) {
    test::expectValidResult(results[t], frames[t].size());
    EXPECT_EQ(results[t].diagnostics.first_frame, t == 0 || t == 3) << t;
    EXPECT_EQ(results[t].diagnostics.reset, t == 3) << t;
  }
  stream.push(frames[0]);
  stream.reset();  // drops frame 0's result
  EXPECT_FALSE(stream.push(frames[1]).has_value());
  EXPECT_TRUE(stream.flush()->diagnostics.first_frame);
}

TEST_P(Stream, ABadFrameIsRefusedAndTheStreamGoesOn) {
  const std::vector<cv::Mat> frames = test::synthFrames(3, 8);
  StreamSegmenter stream(params(), GetParam().threads);
  stream.push(frames[0]);
  EXPECT_THROW(stream.push(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(stream.push(cv::Mat(4, 4, CV_8UC2)), std::invalid_argument);
  const std::optional<Result> first = stream.push(frames[1]);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->diagnostics.first_frame);
  EXPECT_FALSE(stream.flush()->diagnostics.first_frame);
}

// A stream over the work limit runs a pipeline made with lowered parameters; a size change to a
// stream under it makes another, while the previous stream's last frame is still segmented with
// the first (on two threads, at the same time).
TEST_P(Stream, WorkLimitedStreamsGiveTheSegmentersMasks) {
  Params p = params();
  p.alignment_width = 0;
  p.segmentation_width = 0;
  p.edge_cell = 2;         // paper, diff, mog2-comp: 30,500 features at 400x300, 5,300 at 160x120
  p.flow_sample_step = 1;  // dense: 120,000 flow samples at 400x300, 19,200 at 160x120
  std::vector<cv::Mat> frames = test::synthFrames(7, 9, {400, 300});
  for (const size_t t : {0, 1, 5, 6}) cv::resize(frames[t], frames[t], {160, 120});
  Segmenter segmenter(p);
  std::vector<cv::Mat> expected;
  for (size_t t = 0; t < frames.size(); ++t) {
    const Result r = segmenter.process(frames[t]);
    expected.push_back(r.mask);
    // mog2's only cost is its scale, under a megapixel here.
    EXPECT_EQ(r.diagnostics.work_limited, frames[t].cols == 400 && p.method != Method::kMog2) << t;
  }
  // Frame 4, the third of the work-limited size: equal empty masks would prove nothing.
  ASSERT_GT(cv::countNonZero(expected[4]), 0);
  StreamSegmenter stream(p, GetParam().threads);
  EXPECT_TRUE(test::identical(streamed(stream, frames), expected));
}

std::vector<Case> everyMethodOnOneAndTwoThreads() {
  std::vector<Case> cases;
  for (size_t m = 0; m < enumNames<Method>().size(); ++m) {
    for (int threads : {1, 2}) cases.push_back({static_cast<Method>(m), threads});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Stream, ::testing::ValuesIn(everyMethodOnOneAndTwoThreads()),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           std::string name =
                               enumNames<Method>()[static_cast<size_t>(param_info.param.method)];
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name + "_" + std::to_string(param_info.param.threads) + "threads";
                         });

TEST(Stream, RefusesOtherThreadCounts) {
  EXPECT_THROW(StreamSegmenter(Params(), 3), std::invalid_argument);
  EXPECT_THROW(StreamSegmenter(Params(), 0), std::invalid_argument);
}

}  // namespace
}  // namespace movseg
