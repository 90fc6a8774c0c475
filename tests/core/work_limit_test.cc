// The per-frame work limit: the defaults are never touched; the costliest valid parameters are
// lowered into every budget and a frame then takes seconds, not minutes.
#include "core/work_limit.h"

#include <gtest/gtest.h>

#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "reliability/reliability_fixture.h"

namespace movseg {
namespace {

// Every parameter at the end of its range that costs the most: native working scales, the
// densest features, the widest windows, the most hypotheses and rounds, the whole-image cut.
Params costliest() {
  Params p;
  p.method = Method::kPaper;  // the method with the most stages; the tests switch it
  p.alignment_width = 0;
  p.segmentation_width = 0;
  p.max_corners = 100000;
  p.edge_cell = 2;
  p.max_tracked_features = 100000;
  p.lk_window = 101;
  p.lk_levels = 8;
  p.zncc_window = 101;
  p.ransac_iterations = 10000;
  p.ransac_grid = 16;
  p.max_outer_iterations = 100;
  p.gmm_clusters = 256;
  p.difference_blur = 20;
  p.cut_band = 0;
  p.cut_weight = 1000;
  p.geodesic_gamma = 100000;
  return p;
}

TEST(WorkLimit, LeavesTheDefaultsOfEveryMethodAloneAtAnySize) {
  for (size_t m = 0; m < enumNames<Method>().size(); ++m) {
    Params defaults;
    defaults.method = static_cast<Method>(m);
    for (const cv::Size size : {cv::Size(1, 1), cv::Size(320, 240), cv::Size(854, 480),
                                cv::Size(3840, 2160), cv::Size(16384, 16384),
                                cv::Size(100000, 10), cv::Size(1080, 1920), cv::Size(320, 1200)}) {
      EXPECT_FALSE(withinWorkLimit(defaults, size).lowered) << enumNames<Method>()[m] << " " << size;
    }
  }
}

TEST(WorkLimit, LowersTheCostliestParametersIntoEveryBudget) {
  const cv::Size size(3840, 2160);
  const WorkLimit limit = withinWorkLimit(costliest(), size);
  ASSERT_TRUE(limit.lowered);
  const Params& p = limit.params;
  EXPECT_NO_THROW(p.check());
  // Each cost within its budget, and lowered no further than it needs: a limiter that set
  // every parameter to its minimum would pass the upper bounds alone.
  const double align_pixels = p.alignment_width * (p.alignment_width * 2160.0 / 3840);
  EXPECT_LE(align_pixels, 2e6 * 1.001);
  EXPECT_GE(align_pixels, 2e6 * 0.99);
  const double features = p.max_corners + align_pixels / (p.edge_cell * p.edge_cell);
  EXPECT_LE(features, 30000);
  EXPECT_GE(features, 30000 * 0.9);
  const double per_track = 101.0 * 101 * 9 + 101.0 * 101;
  EXPECT_LE(p.max_tracked_features * per_track, 2e7);
  EXPECT_GE(p.max_tracked_features * per_track, 2e7 * 0.99);
  const double ransac = static_cast<double>(p.ransac_iterations) * 100 * p.max_tracked_features;
  EXPECT_LE(ransac, 1e7);
  EXPECT_GE(ransac, 1e7 * 0.99);
  const cv::Size seg(p.segmentation_width, p.segmentation_width * 2160 / 3840);
  EXPECT_LE(seg.area(), 1e6 * 1.001);
  EXPECT_GE(seg.area(), 1e6 * 0.99);
  EXPECT_LE(32.0 * p.cut_band * (seg.width + seg.height), 400000);
  EXPECT_GE(32.0 * (p.cut_band + 1) * (seg.width + seg.height), 400000);  // the widest that fits
  EXPECT_LE(p.difference_blur * seg.area(), 2e7 * 1.001);
  // What is not a cost stays as asked.
  EXPECT_EQ(p.gmm_clusters, 256);
  EXPECT_EQ(p.cut_weight, 1000);
}

// A portrait frame is limited as its landscape twin is: the working scales are set by the
// longer side (core/frame.h, workingSize).
TEST(WorkLimit, TreatsAPortraitFrameAsItsLandscapeTwin) {
  for (const Method method : {Method::kPaper, Method::kDense}) {
    Params p = costliest();
    p.method = method;
    const Params landscape = withinWorkLimit(p, {3840, 2160}).params;
    const Params portrait = withinWorkLimit(p, {2160, 3840}).params;
    EXPECT_EQ(portrait.segmentation_width, landscape.segmentation_width);
    EXPECT_EQ(portrait.alignment_width, landscape.alignment_width);
    EXPECT_EQ(portrait.edge_cell, landscape.edge_cell);
    EXPECT_EQ(portrait.flow_sample_step, landscape.flow_sample_step);
    EXPECT_LT(portrait.segmentation_width, 3840);
  }
}

// Only the method's own stages count: dense tracks no features and cuts no band, mog2 works at
// the segmentation scale alone.
TEST(WorkLimit, LowersOnlyWhatTheMethodUses) {
  const cv::Size size(3840, 2160);
  Params dense = costliest();
  dense.method = Method::kDense;
  const WorkLimit limit = withinWorkLimit(dense, size);
  const Params& p = limit.params;
  EXPECT_NO_THROW(p.check());
  EXPECT_LE(p.segmentation_width * (p.segmentation_width * 2160.0 / 3840), 1e6 * 1.001);
  EXPECT_GE(p.segmentation_width * (p.segmentation_width * 2160.0 / 3840), 1e6 * 0.99);
  const double samples =
      p.segmentation_width * (p.segmentation_width * 2160.0 / 3840) / (p.flow_sample_step * p.flow_sample_step);
  EXPECT_LE(samples, 30000);
  EXPECT_LE(p.ransac_iterations * samples, 1e7);
  EXPECT_GE(p.ransac_iterations * samples, 1e7 * 0.9);
  EXPECT_EQ(p.alignment_width, 0);
  EXPECT_EQ(p.max_corners, 100000);
  EXPECT_EQ(p.cut_band, 0);

  Params mog2 = costliest();
  mog2.method = Method::kMog2;
  EXPECT_FALSE(withinWorkLimit(mog2, {800, 600}).lowered);  // under a megapixel: nothing to lower
  EXPECT_TRUE(withinWorkLimit(mog2, size).lowered);
}

// Unlimited, this pair took 58 s (1.2 GB) for its second frame on the reference machine;
// limited, 0.85 s for the whole test. The frame's work, not its time, is what the limit bounds:
// its features within the budget, every one of them tracked at most.
TEST(WorkLimit, TheCostliestParametersAreLimitedOnAFrame) {
  const std::vector<cv::Mat> frames = test::synthFrames(2, 3, {960, 540});
  Segmenter segmenter(costliest());
  segmenter.process(frames[0]);
  const Result r = segmenter.process(frames[1]);
  EXPECT_TRUE(r.diagnostics.work_limited);
  test::expectValidResult(r, frames[1].size());
  EXPECT_GT(r.diagnostics.features, 1000);  // the frame was aligned from its features
  EXPECT_LE(r.diagnostics.features, 30000);
  EXPECT_LE(r.diagnostics.tracks, r.diagnostics.features);
}

// Dense with every pixel a sample of the camera fit, the narrowest inlier distance and 10,000
// hypotheses, on noise (where no sample set stops RANSAC early): unlimited, the second frame of a
// 960x540 pair took 13 s; limited (a sample every 5 pixels, 482 hypotheses), 0.7 s. The fit's
// samples are those of a 5-pixel grid over the frame, and its hypotheses 10^7 / samples.
TEST(WorkLimit, TheCostliestDenseParametersAreLimitedOnAFrame) {
  Params p = costliest();
  p.method = Method::kDense;
  p.flow_finest_scale = 0;
  p.flow_sample_step = 1;
  p.flow_texture_quantile = 0;
  p.flow_inlier_distance = 0.01;
  p.colour_bits = 5;
  const WorkLimit limit = withinWorkLimit(p, {960, 540});
  EXPECT_EQ(limit.params.flow_sample_step, 5);  // ceil(sqrt(960 * 540 / 30000))
  EXPECT_EQ(limit.params.ransac_iterations, 482);  // 10^7 / (192 * 108)
  Segmenter segmenter(p);
  cv::Mat noise(540, 960, CV_8UC3);
  cv::RNG(1).fill(noise, cv::RNG::UNIFORM, 0, 256);
  segmenter.process(noise);
  cv::RNG(2).fill(noise, cv::RNG::UNIFORM, 0, 256);
  const Result r = segmenter.process(noise);
  EXPECT_TRUE(r.diagnostics.work_limited);
  test::expectValidResult(r, noise.size());
  EXPECT_GT(r.diagnostics.matches, 1000);
  EXPECT_LE(r.diagnostics.matches, 192 * 108);
}

}  // namespace
}  // namespace movseg
