// The dense method end to end: it finds movers on scenes unlike DAVIS (camouflaged, noisy,
// drifting gain), it is causal, and its memory lets go of what has left.
#include <optional>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "accuracy_fixture.h"
#include "movseg/segmenter.h"
#include "movseg/stream_segmenter.h"
#include "reliability/reliability_fixture.h"
#include "test_support.h"

namespace movseg {
namespace {

SynthOptions clip(SynthCamera camera, bool hard) {
  SynthOptions options;
  options.camera = camera;
  options.frames = 30;
  options.seed = 5;
  if (hard) {  // scripts/synth_sets.sh's camo-* sets
    options.camouflage = true;
    options.object_speed_min = 1;
    options.object_speed_max = 3.5;
    options.noise_sigma = 2;
    options.illumination_drift = 0.1;
  }
  return options;
}

class DenseAccuracy : public ::testing::TestWithParam<SynthCamera> {};

// README: every synth camera at 0.95 or more. Measured 0.971-0.991 on the plain clips,
// 0.843-0.939 on the camouflaged ones.
TEST_P(DenseAccuracy, MeanIouAbove095OnPlainAnd082OnCamouflagedObjects) {
  EXPECT_GE(test::meanIou(clip(GetParam(), false), test::withMethod(Method::kDense)), 0.95);
  EXPECT_GE(test::meanIou(clip(GetParam(), true), test::withMethod(Method::kDense)), 0.82);
}

// Grey video (a thermal or night camera) has motion but no colour to learn: measured 0.931
// against 0.971 in colour on this clip.
TEST(DenseAccuracy, GreyFramesKeepMostOfTheAccuracy) {
  EXPECT_GE(
      test::meanIou(clip(SynthCamera::kMix, false), test::withMethod(Method::kDense), test::toGrey),
      0.90);
}

// A lamp that flickers (the frames 8 % darker and brighter in turn) and an exposure that jumps
// (30 % brighter from frame 15 on) change the light, not what moves: measured 0.991 and 0.991,
// 0.989 on the clip as it is; without the change of light fitted (PhotometricCheck::fitLevels),
// 0.140 and 0.955.
TEST(DenseAccuracy, AChangeOfLightIsNotMotion) {
  const SynthOptions pan = clip(SynthCamera::kPan, false);
  const Params dense = test::withMethod(Method::kDense);
  EXPECT_GE(test::meanIou(pan, dense, [](int t, cv::Mat* frame) {
              frame->convertTo(*frame, CV_8U, t % 2 == 0 ? 0.92 : 1.08);
            }),
            0.95);
  EXPECT_GE(test::meanIou(pan, dense, [](int t, cv::Mat* frame) {
              if (t >= 15) frame->convertTo(*frame, CV_8U, 1.3);
            }),
            0.97);
}

// A dash-cam's bonnet: a textured band over the bottom fifth, fixed to the camera, and a
// timestamp-sized box above it. Told to ignore them, `dense` finds the movers of a panning clip
// (measured 0.974; 0.989 on the clip as it is) and of a 3-D scene the camera drives into
// (0.752; 0.745 as it is, its movers partly hidden). Told nothing: 0.634 and 0.612. With the
// camera sampled in the region as elsewhere, the 3-D scene gives 0.599: the still region is
// depth at infinity to the parallax rule.
TEST(DenseAccuracy, WhatIsFixedToTheCameraIsIgnoredWhenSaidSo) {
  SynthOptions forward = clip(SynthCamera::kForward, false);
  forward.scene = SynthScene::kDepth;
  const cv::Size size = forward.size;
  cv::Mat bonnet = test::texture(size, 3), ignored = cv::Mat::zeros(size, CV_8U);
  ignored(cv::Rect(0, size.height * 4 / 5, size.width, size.height / 5)).setTo(255);
  ignored(cv::Rect(8, 8, size.width / 4, 12)).setTo(255);
  const test::FrameChange paste = [&](int, cv::Mat* frame) { bonnet.copyTo(*frame, ignored); };
  const Params dense = test::withMethod(Method::kDense);
  EXPECT_GE(test::meanIou(clip(SynthCamera::kPan, false), dense, paste, ignored), 0.95);
  EXPECT_GE(test::meanIou(forward, dense, paste, ignored), 0.72);
}

// Mean IoU of `params` on `clip` pillarboxed: black bars of `bar` pixels left and right.
double pillarboxedIou(const SynthOptions& clip, const Params& params, int bar) {
  const SynthSequence sequence(clip);
  Segmenter segmenter(params);
  double sum = 0;
  for (int t = 0; t < sequence.size(); ++t) {
    const SynthFrame f = sequence.frame(t);
    cv::Mat frame, truth;
    cv::copyMakeBorder(f.frame, frame, 0, 0, bar, bar, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    cv::copyMakeBorder(f.mask, truth, 0, 0, bar, bar, cv::BORDER_CONSTANT, cv::Scalar(0));
    const Result result = segmenter.process(frame);
    EXPECT_EQ(result.diagnostics.black_bars, params.black_bars) << t;
    const cv::Mat& mask = result.mask;
    if (t > 0) sum += cv::countNonZero(mask & truth) / double(cv::countNonZero(mask | truth));
  }
  return sum / (sequence.size() - 1);
}

// A pillarboxed pan (a 4:3 picture in a 16:9 frame): the bars' still edges against the panned
// scene read as motion and as depth at infinity. Found and left out (Params::black_bars):
// measured 0.985 (0.989 on the clip as it is); with the bars taken for picture
// (black_bars=false, `--black-bars=false`), 0.442.
TEST(DenseAccuracy, BlackBarsAreLeftOut) {
  const SynthOptions pan = clip(SynthCamera::kPan, false);
  Params params = test::withMethod(Method::kDense);
  EXPECT_GE(pillarboxedIou(pan, params, 53), 0.95);
  params.black_bars = false;
  EXPECT_LT(pillarboxedIou(pan, params, 53), 0.7);
}

// The exposure's jump is no scene cut: the mask and its memory are kept (without the change of
// light fitted, frame 15 is a scene cut and its mask empty).
TEST(Dense, ABrighterExposureIsNoSceneCut) {
  const SynthSequence sequence(clip(SynthCamera::kPan, false));
  Segmenter segmenter(test::withMethod(Method::kDense));
  for (int t = 0; t < 20; ++t) {
    cv::Mat frame = sequence.frame(t).frame;
    if (t >= 15) frame.convertTo(frame, CV_8U, 1.3);
    const Result result = segmenter.process(frame);
    EXPECT_FALSE(result.diagnostics.scene_cut) << "frame " << t;
    EXPECT_FALSE(result.diagnostics.reset) << "frame " << t;
    if (t > 2) {  // the movers found before the jump and after it, not a stray pixel
      const cv::Mat& truth = sequence.frame(t).mask;
      const double iou = cv::countNonZero(result.mask & truth) /
                         static_cast<double>(cv::countNonZero(result.mask | truth));
      EXPECT_GT(iou, 0.9) << "frame " << t;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryCamera, DenseAccuracy,
                         ::testing::Values(SynthCamera::kPan, SynthCamera::kZoom,
                                           SynthCamera::kRotate, SynthCamera::kShake,
                                           SynthCamera::kStatic, SynthCamera::kMix),
                         [](const ::testing::TestParamInfo<SynthCamera>& param_info) {
                           return synthCameraName(param_info.param);
                         });

// Causal: on two threads the next frame is analysed while a frame is segmented, so a frame that
// follows could reach the masks before it. Streams that share the first 12 frames and then go
// on differently (the clip, a black frame) give the same 12 masks, those of a run stopped there.
TEST(Dense, MasksOfTheFirstFramesDoNotDependOnLaterOnes) {
  const SynthSequence sequence(clip(SynthCamera::kMix, true));
  const Params params = test::withMethod(Method::kDense);
  const auto first_masks = [&](const std::optional<cv::Mat>& next) {
    StreamSegmenter stream(params, 2);
    std::vector<cv::Mat> masks;
    for (int t = 0; t < 12; ++t) {
      if (std::optional<Result> previous = stream.push(sequence.frame(t).frame)) {
        masks.push_back(previous->mask);
      }
    }
    if (next) {
      if (std::optional<Result> previous = stream.push(*next)) masks.push_back(previous->mask);
    }
    if (std::optional<Result> last = stream.flush()) masks.push_back(last->mask);
    if (next) masks.pop_back();  // the next frame's own
    return masks;
  };
  const std::vector<cv::Mat> stopped = first_masks(std::nullopt);
  ASSERT_EQ(stopped.size(), 12u);
  ASSERT_GT(cv::countNonZero(stopped.back()), 0);  // equal empty masks would prove nothing
  const cv::Mat frame_12 = sequence.frame(12).frame;
  EXPECT_TRUE(test::identical(first_masks(frame_12), stopped));
  EXPECT_TRUE(test::identical(first_masks(cv::Mat(cv::Mat::zeros(frame_12.size(), CV_8UC3))),
                              stopped));
}

// A frame shown twice (a padded frame rate, a dropped frame replaced by the last) is no new
// moment: the repeat gets its original's mask, and the stream goes on as if it had not come —
// the masks after it are those of the stream without it, to the bit.
TEST(Dense, ARepeatedFrameChangesNothing) {
  const SynthSequence sequence(clip(SynthCamera::kMix, true));
  Segmenter plain(test::withMethod(Method::kDense)), repeated(test::withMethod(Method::kDense));
  std::vector<cv::Mat> plain_masks, repeated_masks;
  for (int t = 0; t < 16; ++t) {
    const cv::Mat frame = sequence.frame(t).frame;
    plain_masks.push_back(plain.process(frame).mask);
    const Result result = repeated.process(frame);
    EXPECT_FALSE(result.diagnostics.repeated_frame) << "frame " << t;
    repeated_masks.push_back(result.mask);
    if (t != 10) continue;
    const Result again = repeated.process(frame);
    EXPECT_TRUE(again.diagnostics.repeated_frame);
    ASSERT_GT(cv::countNonZero(again.mask), 0);
    EXPECT_TRUE(test::identical({again.mask}, {result.mask}));
  }
  EXPECT_TRUE(test::identical(plain_masks, repeated_masks));
}

// A textured square crosses a still textured scene and leaves it on the right: once it is
// gone, nothing in the frame moves, and the memory of it must fade within a few frames.
TEST(Dense, AMoverThatLeavesTheViewLeavesTheMask) {
  const cv::Mat scene = test::texture({160, 120}, 3);
  const cv::Mat object = test::texture({30, 30}, 4);
  Segmenter segmenter(test::withMethod(Method::kDense));
  int gone_at = -1;
  for (int t = 0; t < 40; ++t) {
    cv::Mat frame = scene.clone();
    const int x = 60 + 5 * t;
    const cv::Rect inside = cv::Rect(x, 45, 30, 30) & cv::Rect({0, 0}, frame.size());
    if (!inside.empty()) {
      object(cv::Rect({0, 0}, inside.size())).copyTo(frame(inside));
    } else if (gone_at < 0) {
      gone_at = t;
    }
    const int found = cv::countNonZero(segmenter.process(frame).mask);
    if (t == 8) {
      EXPECT_GT(found, 400) << "the moving square is found";
    }
    if (gone_at >= 0 && t >= gone_at + 3) {
      EXPECT_EQ(found, 0) << "frame " << t;
    }
  }
  EXPECT_GT(gone_at, 0);
}

// A plain square of 121 px side crosses a still textured scene at 640x480, twice the working
// size, its left and top sides on odd columns and rows: between the working pixels. The outline
// is placed by the input's own edges (EdgeSnap's output_grey): the mask differs from the square
// in 249 pixels a frame on average over frames 6-19 (180-352; its outline is 484 pixels long);
// with the outline snapped at the working size and scaled up, as before, 378 (314-457).
TEST(Dense, AtTwiceTheWorkingSizeTheOutlineFollowsTheInputsEdges) {
  const cv::Mat scene = test::texture({640, 480}, 3);
  Segmenter segmenter(test::withMethod(Method::kDense));
  int wrong = 0, counted = 0;
  for (int t = 0; t < 20; ++t) {
    cv::Mat frame = scene.clone();
    const cv::Rect square(201 + 5 * t, 181, 121, 121);
    frame(square).setTo(cv::Scalar(40, 200, 230));
    const cv::Mat mask = segmenter.process(frame).mask;
    ASSERT_EQ(mask.size(), frame.size());
    if (t < 6) continue;
    cv::Mat truth = cv::Mat::zeros(frame.size(), CV_8U);
    truth(square).setTo(255);
    wrong += cv::countNonZero(mask != truth);
    ++counted;
  }
  EXPECT_LT(wrong / counted, 300);
}

// Share of `region`'s pixels that `mask` marks.
double shareMarked(const cv::Mat& mask, const cv::Mat& region) {
  return cv::countNonZero(mask & region) / double(cv::countNonZero(region));
}

// A disc of radius 12 px cut from the scene's own texture (camouflaged: only its motion and,
// here and there, its outline tell it apart) moves 2 px a frame while the camera pans `pan` px a
// frame. The share of the disc the mask finds, from frame 8 on.
double smallCamouflagedMoverFound(const Params& params, int pan = 1) {
  const cv::Mat scene = test::texture({480, 240}, 21);
  cv::Mat disc = cv::Mat::zeros(25, 25, CV_8U);
  cv::circle(disc, {12, 12}, 12, 255, cv::FILLED);
  const cv::Mat skin = scene(cv::Rect(400, 200, 25, 25));
  Segmenter segmenter(params);
  double found = 0;
  int counted = 0;
  for (int t = 0; t < 30; ++t) {
    cv::Mat frame = scene(cv::Rect(pan * t, 0, 320, 240)).clone();
    const cv::Rect at(100 + 2 * t, 100, 25, 25);
    skin.copyTo(frame(at), disc);
    cv::Mat truth = cv::Mat::zeros(frame.size(), CV_8U);
    disc.copyTo(truth(at));
    const cv::Mat mask = segmenter.process(frame).mask;
    if (t < 8) continue;
    found += shareMarked(mask, truth);
    ++counted;
  }
  return found / counted;
}

// The cut keeps a new mover only where its evidence outweighs its outline's edges: at
// smoothness 14 this small camouflaged mover is never found. (At 10, the previous default, it
// was not found either until the colour model learnt the background from what the pair alone
// calls static: now 0.64; docs/design.md, "The cut's smoothness".)
TEST(Dense, ASmallCamouflagedMoverIsFound) {
  Params params = test::withMethod(Method::kDense);
  EXPECT_GT(smallCamouflagedMoverFound(params), 0.8);  // measured 0.95
  params.smoothness = 14;
  params.motion_regions = false;  // the cut alone (the next test has the rule)
  EXPECT_LT(smallCamouflagedMoverFound(params), 0.1);  // measured 0
}

// The same disc is found even where its outline costs too much for the cut (smoothness 14): its
// motion apart from the mask, over one flow patch's evidence on two pairs in a row, with a unary
// that prefers foreground as a whole, joins the mask (Params::motion_regions), the camera still
// or panning; not without the rule.
TEST(Dense, ASmallMoverIsFoundWhateverItsOutlineCosts) {
  Params params = test::withMethod(Method::kDense);
  params.smoothness = 14;
  EXPECT_GT(smallCamouflagedMoverFound(params, 0), 0.7);  // still: measured 0.81
  EXPECT_GT(smallCamouflagedMoverFound(params, 1), 0.7);  // panning: measured 0.89
  params.motion_regions = false;
  EXPECT_LT(smallCamouflagedMoverFound(params, 0), 0.1);  // measured 0
  EXPECT_LT(smallCamouflagedMoverFound(params, 1), 0.1);  // measured 0
}

// A sideways dolly past near posts: the far wall slides 2 px a frame, four posts in front of it
// 5 to 7 px (parallax: faster the nearer, all along the direction of travel), and a red square
// moves across that direction. Its frame t, and the posts' and the mover's pixels in it.
struct DollyFrame {
  cv::Mat image, posts, mover;
};

DollyFrame dollyPastPosts(int t) {
  const cv::Size size(320, 240);
  static const cv::Mat wall = test::texture({size.width + 200, size.height}, 11);
  static const cv::Mat post = test::texture({16, size.height}, 12);
  static const cv::Mat square = test::texture({40, 40}, 13) / 2 + cv::Scalar(0, 0, 120);  // red
  DollyFrame frame{wall(cv::Rect(2 * t, 0, size.width, size.height)).clone(),
                   cv::Mat::zeros(size, CV_8U), cv::Mat::zeros(size, CV_8U)};
  const cv::Rect mover(150, 40 + 3 * t, 40, 40);
  square.copyTo(frame.image(mover));
  frame.mover(mover).setTo(255);
  for (int i = 0; i < 4; ++i) {
    const int x = 60 + 80 * i - (5 + i % 3) * t;  // nearer posts move faster
    const cv::Rect at = cv::Rect(x, 0, 16, size.height) & cv::Rect({0, 0}, size);
    if (at.empty()) continue;
    post(cv::Rect(at.x - x, 0, at.width, at.height)).copyTo(frame.image(at));
    frame.posts(at).setTo(255);
    frame.mover(at).setTo(0);  // the posts are nearer than the square
  }
  return frame;
}

// Shares of the posts and of the mover that the mask marks, over the frames after the first of
// a 30-frame dolly, and the pairs that read depth.
struct DollyScores {
  double posts_marked = 0, mover_found = 0;
  int parallax_pairs = 0, first_parallax = -1;
};

DollyScores segmentDolly(const Params& params) {
  Segmenter segmenter(params);
  DollyScores scores;
  int counted = 0;
  for (int t = 0; t < 30; ++t) {
    const DollyFrame frame = dollyPastPosts(t);
    const Result result = segmenter.process(frame.image);
    scores.parallax_pairs += result.diagnostics.parallax;
    if (result.diagnostics.parallax && scores.first_parallax < 0) scores.first_parallax = t;
    if (t == 0) continue;
    const cv::Mat posts = frame.posts & ~frame.mover;
    scores.posts_marked += shareMarked(result.mask, posts);
    scores.mover_found += shareMarked(result.mask, frame.mover);
    ++counted;
  }
  scores.posts_marked /= counted;
  scores.mover_found /= counted;
  return scores;
}

TEST(Dense, ADollyPastNearPostsReadsDepthAndKeepsThePostsOut) {
  const DollyScores plane_and_parallax = segmentDolly(test::withMethod(Method::kDense));
  // Read from the first pair, whose posts move with the plane: judged by that pair alone, not
  // as one of five of which the four not yet seen showed no depth (then read from the third,
  // the posts took 6.5 % of their pixels into the masks, which memory held).
  EXPECT_EQ(plane_and_parallax.first_parallax, 1);
  EXPECT_GE(plane_and_parallax.parallax_pairs, 25);
  EXPECT_LT(plane_and_parallax.posts_marked, 0.01);
  EXPECT_GT(plane_and_parallax.mover_found, 0.9);
  Params plane_only = test::withMethod(Method::kDense);
  plane_only.parallax = false;  // the posts then move against the plane, as movers do
  EXPECT_GT(segmentDolly(plane_only).posts_marked, 0.3);
}

// A panning view whose top and bottom bands stand still in the image (45 % of the rows): to plane
// + parallax a scene at infinity, against the plane, as a large mover the camera follows. With
// no other pair to outvote it, the first pair does not read it as depth; from the third, most of
// the pairs seen show it.
TEST(Dense, DepthAgainstThePlaneIsNotReadOnTheFirstPair) {
  const cv::Size size(320, 240);
  const cv::Mat wall = test::texture({size.width + 100, size.height}, 11);
  const cv::Mat bands = test::texture(size, 14);
  Segmenter segmenter(test::withMethod(Method::kDense));
  std::vector<int> parallax;
  for (int t = 0; t < 6; ++t) {
    cv::Mat frame = wall(cv::Rect(2 * t, 0, size.width, size.height)).clone();
    bands.rowRange(0, 54).copyTo(frame.rowRange(0, 54));
    bands.rowRange(186, 240).copyTo(frame.rowRange(186, 240));
    parallax.push_back(segmenter.process(frame).diagnostics.parallax);
  }
  EXPECT_EQ(parallax, (std::vector<int>{0, 0, 0, 1, 1, 1}));
}

// Movers on a plane agree on epipoles of their own, but locally: no pair reads depth.
TEST(Dense, PlanarScenesWithMoversNeverReadDepth) {
  for (const SynthCamera camera : {SynthCamera::kPan, SynthCamera::kZoom, SynthCamera::kRotate,
                                   SynthCamera::kShake, SynthCamera::kStatic, SynthCamera::kMix}) {
    for (const bool hard : {false, true}) {
      const SynthSequence sequence(clip(camera, hard));
      Segmenter segmenter(test::withMethod(Method::kDense));
      for (int t = 0; t < sequence.size(); ++t) {
        EXPECT_FALSE(segmenter.process(sequence.frame(t).frame).diagnostics.parallax)
            << synthCameraName(camera) << (hard ? " camouflaged" : "") << ", frame " << t;
      }
    }
  }
}

}  // namespace
}  // namespace movseg
