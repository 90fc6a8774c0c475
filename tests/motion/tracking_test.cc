// §3.1 track filters: ZNCC (eq. 2) and forward–backward distance, each against its median.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "motion/tracking.h"
#include "test_support.h"

namespace movseg {
namespace {

TEST(Tracking, ZnccIsOneForTheSamePatchAndInvariantToGainAndOffset) {
  const cv::Mat image = test::texture({64, 64}, 3);
  cv::Mat grey, brighter;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(brighter, CV_8U, 0.8, 20);
  EXPECT_NEAR(zncc(grey, {30, 30}, grey, {30, 30}, 11), 1.0, 1e-5);
  EXPECT_NEAR(zncc(grey, {30, 30}, brighter, {30, 30}, 11), 1.0, 0.02);
  EXPECT_LT(zncc(grey, {30, 30}, grey, {12, 45}, 11), 0.5);
  const cv::Mat flat(64, 64, CV_8U, cv::Scalar(7));
  EXPECT_EQ(zncc(flat, {30, 30}, flat, {30, 30}, 11), 0.0f);
}

// Real LK tracks on a translated texture, some of them corrupted afterwards; the filters must
// remove every corrupted one.
class TrackFilter : public ::testing::Test {
 protected:
  void SetUp() override {
    cv::Mat colour = test::texture({320, 240}, 5);
    cv::cvtColor(colour, prev_, cv::COLOR_BGR2GRAY);
    const cv::Matx23d shift(1, 0, 3, 0, 1, 2);
    cv::warpAffine(prev_, cur_, shift, prev_.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    Params params;
    std::vector<cv::Mat> prev_pyr, cur_pyr;
    const cv::Size window(params.lk_window, params.lk_window);
    cv::buildOpticalFlowPyramid(prev_, prev_pyr, window, params.lk_levels);
    cv::buildOpticalFlowPyramid(cur_, cur_pyr, window, params.lk_levels);
    std::vector<cv::Point2f> points;
    for (int y = 30; y < 210; y += 15)
      for (int x = 30; x < 290; x += 15) points.emplace_back(static_cast<float>(x), static_cast<float>(y));
    tracks_ = trackForwardBackward(prev_pyr, cur_pyr, points, cv::Matx33d::eye(), params);
    ASSERT_GT(tracks_.size(), 150u);
  }
  cv::Mat prev_, cur_;
  std::vector<Track> tracks_;
};

TEST_F(TrackFilter, ZnccRemovesTracksPointingElsewhere) {
  std::vector<size_t> corrupted;
  for (size_t i = 0; i < tracks_.size(); i += 10) {
    tracks_[i].cur += cv::Point2f(9, -7);  // a wrong correspondence with a perfect FB distance
    tracks_[i].zncc = zncc(prev_, tracks_[i].prev, cur_, tracks_[i].cur, 11);
    tracks_[i].fb_distance = 0;
    corrupted.push_back(i);
  }
  const std::vector<Track> kept = filterTracks(tracks_);
  for (size_t i : corrupted) {
    for (const Track& t : kept) EXPECT_NE(t.cur, tracks_[i].cur) << "corrupted track " << i << " kept";
  }
  EXPECT_GT(kept.size(), tracks_.size() / 5);
}

TEST_F(TrackFilter, ForwardBackwardDistanceRemovesInconsistentTracks) {
  std::vector<cv::Point2f> corrupted;
  for (size_t i = 0; i < tracks_.size(); i += 10) {
    tracks_[i].fb_distance = 5.0f;  // backward flow did not come home
    tracks_[i].zncc = 1.0f;
    corrupted.push_back(tracks_[i].prev);
  }
  const std::vector<Track> kept = filterTracks(tracks_);
  for (const Track& t : kept) {
    for (const cv::Point2f& p : corrupted) EXPECT_NE(t.prev, p);
  }
  EXPECT_GT(kept.size(), tracks_.size() / 5);  // a filter that kept nothing would pass the above
}

TEST(Tracking, MedianRulesKeepAtMostHalfOfTheTracks) {
  std::vector<Track> tracks(100);
  for (int i = 0; i < 100; ++i) {
    tracks[static_cast<size_t>(i)].zncc = static_cast<float>(i) / 100.f;
    tracks[static_cast<size_t>(i)].fb_distance = static_cast<float>(i) / 100.f;
  }
  // High ZNCC comes with high FB distance here, so the two medians (both the 51st value, 0.5)
  // leave the one track at both: ZNCC >= 0.5 and FB distance <= 0.5.
  const std::vector<Track> kept = filterTracks(tracks);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].zncc, 0.5f);
  EXPECT_TRUE(filterTracks({}).empty());
}

}  // namespace
}  // namespace movseg
