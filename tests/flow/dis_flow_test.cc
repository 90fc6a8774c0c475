#include "flow/dis_flow.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "flow/dense_flow.h"
#include "test_support.h"

namespace movseg {
namespace {

// DisFlow::calc on two images, each prepared here.
void calcImages(DisFlow* dis, const cv::Mat& from, const cv::Mat& to, const cv::Mat& initial,
                cv::Mat* flow) {
  DisFrame prepared_from, prepared_to;
  dis->prepare(from, &prepared_from);
  dis->prepare(to, &prepared_to);
  dis->calc(prepared_from, prepared_to, initial, flow);
}

// movseg's finest scale (params.def: flow_finest_scale).
constexpr int kFinest = 1;

// `image` moved by `warp`: the result at p is image(warp(p)), so that the flow from the result to
// `image` is warp(p) - p.
cv::Mat warped(const cv::Mat& image, const cv::Matx23d& warp) {
  cv::Mat out;
  cv::warpAffine(image, out, warp, image.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REFLECT);
  return out;
}

struct FlowError {
  double mean = 0;      // mean end-point error, pixels
  double over_half = 0;  // the fraction of pixels off by more than half a pixel
};

// `flow` against `truth` (both CV_32FC2) inside `region`.
FlowError flowError(const cv::Mat& flow, const cv::Mat& truth, const cv::Rect& region) {
  cv::Mat difference = flow(region) - truth(region);
  std::vector<cv::Mat> xy;
  cv::split(difference, xy);
  cv::Mat distance;
  cv::magnitude(xy[0], xy[1], distance);
  const double over_half = cv::countNonZero(distance > 0.5);
  return {cv::mean(distance)[0], over_half / region.area()};
}

// The flow of `warp` at every pixel: warp(p) - p.
cv::Mat warpFlow(const cv::Matx23d& warp, cv::Size size) {
  cv::Mat flow(size, CV_32FC2);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const double to_x = warp(0, 0) * x + warp(0, 1) * y + warp(0, 2);
      const double to_y = warp(1, 0) * x + warp(1, 1) * y + warp(1, 2);
      flow.at<cv::Vec2f>(y, x) =
          cv::Vec2f(static_cast<float>(to_x - x), static_cast<float>(to_y - y));
    }
  }
  return flow;
}

cv::Mat zeroFlow(cv::Size size) { return cv::Mat::zeros(size, CV_32FC2); }

cv::Mat openCvFlow(const cv::Mat& from, const cv::Mat& to, const cv::Mat& initial) {
  cv::Mat flow = initial.clone();
  openCvDis(kFinest)->calc(from, to, flow);
  return flow;
}

cv::Mat ourFlow(const cv::Mat& from, const cv::Mat& to, const cv::Mat& initial) {
  DisFlow dis(kFinest);
  cv::Mat flow;
  calcImages(&dis, from, to, initial, &flow);
  return flow;
}

// Away from the border, where the warp read pixels reflected and patches run out.
cv::Rect interior(cv::Size size) { return {16, 16, size.width - 32, size.height - 32}; }

// A sub-pixel translation of a texture is found to a twentieth of a pixel: measured mean error
// 0.055 px at 320x240 and 0.054 at 203x117 (a size that is no multiple of the patch stride), no
// pixel of the interior off by half a pixel.
TEST(DisFlow, FindsASubPixelTranslation) {
  for (const cv::Size size : {cv::Size(320, 240), cv::Size(203, 117)}) {
    const cv::Mat previous = test::greyTexture(size, 7);
    const cv::Matx23d shift(1, 0, 2.3, 0, 1, -1.6);
    const cv::Mat current = warped(previous, shift);
    const cv::Mat flow = ourFlow(current, previous, zeroFlow(size));
    ASSERT_EQ(flow.size(), size);
    ASSERT_EQ(flow.type(), CV_32FC2);
    const FlowError error = flowError(flow, warpFlow(shift, size), interior(size));
    EXPECT_LT(error.mean, 0.07) << size;
    EXPECT_LT(error.over_half, 0.001) << size;
  }
}

// A zoom with a rotation and a shift (up to 6 px at the corners): measured mean error 0.100 px,
// no pixel of the interior off by half a pixel.
TEST(DisFlow, FollowsAZoomAndARotation) {
  const cv::Size size(320, 240);
  const cv::Mat previous = test::greyTexture(size, 8);
  const double scale = 1.03, angle = 0.015, cx = size.width / 2.0, cy = size.height / 2.0;
  const double a = scale * std::cos(angle), b = scale * std::sin(angle);
  const cv::Matx23d zoom(a, -b, cx - a * cx + b * cy + 1.2, b, a, cy - b * cx - a * cy - 0.4);
  const cv::Mat flow = ourFlow(warped(previous, zoom), previous, zeroFlow(size));
  const FlowError error = flowError(flow, warpFlow(zoom, size), interior(size));
  EXPECT_LT(error.mean, 0.13);
  EXPECT_LT(error.over_half, 0.005);
}

// The flows equal, to the bit (README): the same float operations in the same order as
// OpenCV 4.6's SSE2 code, which Debian's OpenCV runs.
void expectSameFlow(const cv::Mat& ours, const cv::Mat& opencv, const std::string& what) {
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  ASSERT_EQ(ours.type(), opencv.type()) << what;
  EXPECT_EQ(cv::norm(ours, opencv, cv::NORM_INF), 0.0) << what;
}

// The same pair through OpenCV's DIS at the same settings.
void expectOpenCvsFlow(const cv::Mat& from, const cv::Mat& to, const cv::Mat& initial,
                       const std::string& what) {
  expectSameFlow(ourFlow(from, to, initial), openCvFlow(from, to, initial), what);
}

TEST(DisFlow, AgreesWithOpenCvOnSyntheticPairs) {
  for (const cv::Size size : {cv::Size(320, 240), cv::Size(320, 180), cv::Size(203, 117),
                              cv::Size(854, 480)}) {
    const cv::Mat previous = test::greyTexture(size, 11);
    // A camera that zooms and pans, and a square that moves on its own.
    cv::Mat current = warped(previous, cv::Matx23d(1.02, 0.01, -2.5, -0.01, 1.02, 1.5));
    const cv::Rect square(size.width / 3, size.height / 3, size.width / 5, size.height / 5);
    warped(previous, cv::Matx23d(1, 0, 6, 0, 1, -4))(square).copyTo(current(square));
    const std::string what = std::to_string(size.width) + "x" + std::to_string(size.height);
    expectOpenCvsFlow(current, previous, zeroFlow(size), what + " from rest");
    // Warm: from a flow of the right kind but off by a pixel and a half.
    cv::Mat initial = warpFlow(cv::Matx23d(1.02, 0.01, -1.0, -0.01, 1.02, 0.5), size);
    expectOpenCvsFlow(current, previous, initial, what + " warm");
  }
}

// Frames too small for the finest scale (under ~46 pixels on the longer side): OpenCV picks its
// scales from the width then, and so does DisFlow (OpenCV's first call; it keeps them after).
TEST(DisFlow, AgreesWithOpenCvOnTinyFrames) {
  for (const cv::Size size : {cv::Size(16, 16), cv::Size(40, 30), cv::Size(45, 17),
                              cv::Size(17, 44), cv::Size(64, 16)}) {
    const cv::Mat previous = test::greyTexture(size, 12);
    const cv::Mat current = warped(previous, cv::Matx23d(1, 0, 1.5, 0, 1, -0.5));
    expectOpenCvsFlow(current, previous, zeroFlow(size),
                      std::to_string(size.width) + "x" + std::to_string(size.height));
  }
}

// The DAVIS frames movseg sees (the working width of 320 and the stored 854x480), pair after
// pair, each starting from the previous pair's flow as DenseFlow does.
TEST(DisFlow, AgreesWithOpenCvOnDavisPairs) {
  const std::vector<std::string> files = test::davisFrames("dog", 6);
  if (files.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  for (const cv::Size size : {cv::Size(320, 180), cv::Size(320, 240), cv::Size()}) {
    cv::Mat previous, initial;
    for (const std::string& file : files) {
      cv::Mat grey = cv::imread(file, cv::IMREAD_GRAYSCALE);
      ASSERT_FALSE(grey.empty()) << file;
      if (!size.empty()) cv::resize(grey, grey, size, 0, 0, cv::INTER_AREA);
      if (!previous.empty()) {
        if (initial.empty()) initial = zeroFlow(grey.size());
        expectOpenCvsFlow(grey, previous, initial, file);
        initial = openCvFlow(grey, previous, initial);
      }
      previous = grey;
    }
  }
}

// A large motion of a texture without coarse structure, which the pyramid alone does not find:
// given the right flow to start from, the search keeps it (as OpenCV's, which tries the initial
// flow at every patch of every level). Measured mean error 0.054 px warm, 18.6 px from rest.
TEST(DisFlow, StartsFromTheInitialFlow) {
  const cv::Size size(320, 240);
  cv::Mat noise(size, CV_32F), coarse;
  cv::RNG(5).fill(noise, cv::RNG::UNIFORM, 0, 1);
  cv::GaussianBlur(noise, noise, {0, 0}, 0.8);
  cv::GaussianBlur(noise, coarse, {0, 0}, 4);
  cv::Mat previous;
  cv::Mat(noise - coarse).convertTo(previous, CV_8U, 600, 128);
  const cv::Matx23d shift(1, 0, 14.4, 0, 1, -9.7);
  const cv::Mat current = warped(previous, shift);
  const cv::Mat truth = warpFlow(shift, size);
  const FlowError from_rest = flowError(ourFlow(current, previous, zeroFlow(size)), truth,
                                        interior(size));
  const FlowError warm = flowError(ourFlow(current, previous, truth), truth, interior(size));
  EXPECT_GT(from_rest.mean, 5.0);
  EXPECT_LT(warm.mean, 0.08);
  expectOpenCvsFlow(current, previous, truth, "warm");
}

// The initial flow may be the output itself: it is read before the flow is written.
TEST(DisFlow, TheInitialFlowMayBeTheOutput) {
  const cv::Size size(160, 120);
  const cv::Mat previous = test::greyTexture(size, 13);
  const cv::Mat current = warped(previous, cv::Matx23d(1, 0, 3.2, 0, 1, 1.1));
  const cv::Mat initial = warpFlow(cv::Matx23d(1, 0, 2.5, 0, 1, 1.5), size);
  DisFlow dis(kFinest);
  cv::Mat separate, in_place = initial.clone();
  calcImages(&dis, current, previous, initial, &separate);
  calcImages(&dis, current, previous, in_place, &in_place);
  EXPECT_EQ(cv::norm(separate, in_place, cv::NORM_INF), 0.0);
}

// An initial flow of NaN (a caller's bug) lands on the border, scores a NaN SSD and never wins:
// the flow is the one without an initial flow. (OpenCV's DIS reads past its images there.)
TEST(DisFlow, ANaNInitialFlowNeverWins) {
  const cv::Size size(160, 120);
  const cv::Mat previous = test::greyTexture(size, 15);
  const cv::Mat current = warped(previous, cv::Matx23d(1, 0, 2.2, 0, 1, -1.3));
  const cv::Mat nan(size, CV_32FC2, cv::Scalar::all(std::numeric_limits<double>::quiet_NaN()));
  const cv::Mat flow = ourFlow(current, previous, nan);
  EXPECT_EQ(cv::norm(flow, ourFlow(current, previous, cv::Mat()), cv::NORM_INF), 0.0);
}

// A prepared frame serves as the first image of one pair and the second of the next: the flows
// are those of pairs prepared afresh.
TEST(DisFlow, APreparedFrameServesTwoPairs) {
  const cv::Size size(200, 150);
  const cv::Mat a = test::greyTexture(size, 14);
  const cv::Mat b = warped(a, cv::Matx23d(1, 0, 1.7, 0, 1, 0.6));
  const cv::Mat c = warped(b, cv::Matx23d(1, 0, -0.8, 0, 1, 2.1));
  DisFlow dis(kFinest);
  DisFrame frames[3];
  dis.prepare(a, &frames[0]);
  dis.prepare(b, &frames[1]);
  dis.prepare(c, &frames[2]);
  cv::Mat ba, cb;
  dis.calc(frames[1], frames[0], zeroFlow(size), &ba);
  dis.calc(frames[2], frames[1], ba, &cb);
  EXPECT_EQ(cv::norm(ba, ourFlow(b, a, zeroFlow(size)), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(cb, ourFlow(c, b, ba), cv::NORM_INF), 0.0);
}

// ---- DenseFlow: the stream ----------------------------------------------------------------------

// Frames of a texture panning, with a square moving on its own.
std::vector<cv::Mat> clip(cv::Size size, int frames) {
  const cv::Mat scene = test::greyTexture(size + cv::Size(64, 64), 21);
  const cv::Mat mover = test::greyTexture({size.width / 5, size.height / 5}, 22);
  std::vector<cv::Mat> out;
  for (int t = 0; t < frames; ++t) {
    const cv::Matx23d pan(1, 0, 1.3 * t, 0, 1, 0.7 * t);
    cv::Mat frame = warped(scene, pan)(cv::Rect({0, 0}, size)).clone();
    mover.copyTo(frame(cv::Rect({size.width / 3 + 3 * t, size.height / 3}, mover.size())));
    out.push_back(frame);
  }
  return out;
}

// DenseFlow gives OpenCV's flows as the DenseFlow that drove cv::DISOpticalFlow gave them: the
// first frame none, then each pair from the previous pair's flow (from rest for the first).
TEST(DenseFlow, GivesOpenCvsFlowsOverAStream) {
  const std::vector<cv::Mat> frames = clip({320, 180}, 6);
  DenseFlow dense(kFinest);
  const cv::Ptr<cv::DISOpticalFlow> reference = openCvDis(kFinest);
  cv::Mat previous_flow;
  for (size_t t = 0; t < frames.size(); ++t) {
    cv::Mat flow;
    dense.next(frames[t], &flow);
    if (t == 0) {
      EXPECT_TRUE(flow.empty());
      continue;
    }
    cv::Mat expected = previous_flow.empty() ? zeroFlow(frames[t].size()) : previous_flow.clone();
    reference->calc(frames[t], frames[t - 1], expected);
    expectSameFlow(flow, expected, "pair " + std::to_string(t));
    previous_flow = expected;
  }
}

// Under 16 pixels a side there is no flow; at 16 there is.
TEST(DenseFlow, TinyFramesHaveNoFlow) {
  for (const cv::Size size : {cv::Size(15, 40), cv::Size(40, 15), cv::Size(8, 8)}) {
    DenseFlow dense(kFinest);
    cv::Mat flow;
    dense.next(test::greyTexture(size, 1), &flow);
    dense.next(test::greyTexture(size, 2), &flow);
    EXPECT_TRUE(flow.empty()) << size;
  }
  DenseFlow dense(kFinest);
  cv::Mat flow;
  dense.next(test::greyTexture({16, 16}, 1), &flow);
  dense.next(test::greyTexture({16, 16}, 2), &flow);
  EXPECT_EQ(flow.size(), cv::Size(16, 16));
}

// A frame of another size has no flow, and the stream restarts from it: the next flows are those
// of a DenseFlow that started there.
TEST(DenseFlow, AFrameOfANewSizeRestarts) {
  const std::vector<cv::Mat> large = clip({320, 240}, 3), small = clip({200, 150}, 3);
  DenseFlow dense(kFinest), fresh(kFinest);
  cv::Mat flow, expected;
  for (const cv::Mat& frame : large) dense.next(frame, &flow);
  ASSERT_FALSE(flow.empty());
  for (size_t t = 0; t < small.size(); ++t) {
    dense.next(small[t], &flow);
    fresh.next(small[t], &expected);
    EXPECT_EQ(flow.empty(), t == 0);
    if (t > 0) {
      EXPECT_EQ(cv::norm(flow, expected, cv::NORM_INF), 0.0) << t;
    }
  }
}

// reset() forgets the previous frame: the next has no flow.
TEST(DenseFlow, ResetForgetsThePreviousFrame) {
  const std::vector<cv::Mat> frames = clip({160, 120}, 3);
  DenseFlow dense(kFinest);
  cv::Mat flow;
  dense.next(frames[0], &flow);
  dense.next(frames[1], &flow);
  ASSERT_FALSE(flow.empty());
  dense.reset();
  dense.next(frames[2], &flow);
  EXPECT_TRUE(flow.empty());
}

}  // namespace
}  // namespace movseg
