// Scene cuts: the rule on difference images, and on real cuts between six DAVIS sequences
// (docs/reliability.md has the figure for all fifteen; skipped without the data).
#include "classify/scene_cut.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "io/frame_source.h"
#include "movseg/segmenter.h"
#include "test_support.h"

namespace movseg {
namespace {

TEST(SceneCut, TheMedianDifferenceOverTheCoveredPixelsDecides) {
  const cv::Size size(40, 30);
  const cv::Matx33d same = cv::Matx33d::eye();
  EXPECT_FALSE(isSceneCut(cv::Mat(size, CV_32F, cv::Scalar(0)), same));
  EXPECT_FALSE(isSceneCut(cv::Mat(size, CV_32F, cv::Scalar(kSceneCutMedianDifference)), same));
  EXPECT_TRUE(isSceneCut(cv::Mat(size, CV_32F, cv::Scalar(kSceneCutMedianDifference + 1)), same));
  cv::Mat part(size, CV_32F, cv::Scalar(0));
  part.rowRange(0, 14) = 10000;  // less than half the picture differs: something moved
  EXPECT_FALSE(isSceneCut(part, same));
  part.rowRange(0, 16) = 10000;  // more than half
  EXPECT_TRUE(isSceneCut(part, same));
  EXPECT_FALSE(isSceneCut(cv::Mat(), same));
}

TEST(SceneCut, AModelThatMapsThePreviousFrameMostlyAwayIsACut) {
  const cv::Mat flat(30, 40, CV_32F, cv::Scalar(0));  // the uncovered pixels read d = 0
  EXPECT_FALSE(isSceneCut(flat, cv::Matx33d(1, 0, 15, 0, 1, 0, 0, 0, 1)));  // 62 % covered
  EXPECT_TRUE(isSceneCut(flat, cv::Matx33d(1, 0, 25, 0, 1, 0, 0, 0, 1)));   // 37 % covered
  EXPECT_TRUE(isSceneCut(flat, cv::Matx33d(0.2, 0, 0, 0, 0.2, 0, 0, 0, 1)));
}

std::vector<std::string> frameFiles(const std::string& sequence) {
  return listImages(sequence + "/frames");
}

// Every ordered pair of the DAVIS sequences here joined at a cut (frame 10 of one, then frame 0
// of the other) is flagged; no pair of consecutive frames of the first 20 of each sequence is.
TEST(SceneCut, FlagsRealCutsAndNoConsecutiveFrames) {
  std::vector<std::string> sequences;
  for (const char* name : {"blackswan", "breakdance", "car-roundabout", "dance-twirl", "dog",
                           "drift-straight"}) {
    const std::string folder = test::davisSequence(name);
    if (!folder.empty()) sequences.push_back(folder);
  }
  if (sequences.size() < 2) GTEST_SKIP() << "DAVIS 2016 is not here";
  int cuts = 0, flagged = 0, pairs = 0, false_cuts = 0;
  for (const std::string& a : sequences) {
    const std::vector<std::string> files = frameFiles(a);
    Segmenter segmenter;
    for (size_t i = 0; i < 20 && i < files.size(); ++i) {
      const Result r = segmenter.process(cv::imread(files[i]));
      pairs += i > 0;
      false_cuts += r.diagnostics.scene_cut;
      EXPECT_FALSE(r.diagnostics.scene_cut) << files[i];
    }
    for (const std::string& b : sequences) {
      if (a == b) continue;
      Segmenter cut;
      cut.process(cv::imread(files[10]));
      const Result r = cut.process(cv::imread(frameFiles(b)[0]));
      ++cuts;
      flagged += r.diagnostics.scene_cut;
      EXPECT_TRUE(r.diagnostics.scene_cut) << a << " > " << b;
      if (r.diagnostics.scene_cut) {
        EXPECT_EQ(cv::countNonZero(r.mask), 0);
      }
    }
  }
  std::printf("scene cuts flagged: %d of %d; consecutive pairs flagged: %d of %d\n", flagged, cuts,
              false_cuts, pairs);
}

}  // namespace
}  // namespace movseg
