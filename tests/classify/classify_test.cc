// §3.2 feature classification: eq. (3) and the colour-GMM refinement of eq. (5).
#include <cmath>

#include <gtest/gtest.h>

#include "classify/classify.h"
#include "classify/colour_gmm.h"

namespace movseg {
namespace {

TEST(Classify, Equation3ThresholdsTheDifferenceAtThePoints) {
  cv::Mat d(10, 10, CV_32F, cv::Scalar(10));
  d.at<float>(2, 3) = 500;
  const auto labels = classifyByDifference(d, {{3, 2}, {7, 7}}, 400);
  EXPECT_EQ(labels[0], FeatureLabel::kForeground);
  EXPECT_EQ(labels[1], FeatureLabel::kBackground);
}

TEST(Classify, LambdaRisesWithTheResidualOnStaticPoints) {
  Params params;
  cv::Mat d(40, 40, CV_32F, cv::Scalar(5));
  d(cv::Rect(0, 0, 40, 20)).setTo(300);  // top half: badly aligned static texture
  const std::vector<cv::Point2f> bottom{{5, 30}, {15, 30}, {25, 30}, {35, 30}};
  const std::vector<cv::Point2f> mixed{{5, 30}, {15, 10}, {25, 10}, {35, 10}};
  EXPECT_DOUBLE_EQ(chooseLambda(d, bottom, params), params.lambda);
  EXPECT_DOUBLE_EQ(chooseLambda(d, mixed, params), 300 * params.lambda_residual_factor);
  EXPECT_DOUBLE_EQ(chooseLambda(d, {}, params), params.lambda);
}

TEST(Classify, FarthestPointClusteringSeparatesDistantGroups) {
  std::vector<cv::Vec3f> samples;
  for (int i = 0; i < 5; ++i) samples.emplace_back(10.f + i, 10, 10);    // group A
  for (int i = 0; i < 5; ++i) samples.emplace_back(200.f + i, 10, 10);   // group B
  for (int i = 0; i < 5; ++i) samples.emplace_back(10, 200.f + i, 10);   // group C
  const std::vector<int> cluster = farthestPointClusters(samples, 3);
  for (int g = 0; g < 3; ++g)
    for (int i = 1; i < 5; ++i) EXPECT_EQ(cluster[g * 5 + i], cluster[g * 5]);
  EXPECT_NE(cluster[0], cluster[5]);
  EXPECT_NE(cluster[0], cluster[10]);
  EXPECT_NE(cluster[5], cluster[10]);
}

TEST(Classify, GmmOfIdenticalColoursStaysFinite) {
  const ColourGmm gmm = ColourGmm::fit(std::vector<cv::Vec3f>(20, cv::Vec3f(50, 50, 50)), 5);
  EXPECT_TRUE(std::isfinite(gmm.logLikelihood({50, 50, 50})));
  EXPECT_TRUE(std::isfinite(gmm.logLikelihood({255, 0, 255})));
  EXPECT_GT(gmm.logLikelihood({50, 50, 50}), gmm.logLikelihood({255, 0, 255}));
  EXPECT_TRUE(ColourGmm::fit({}, 5).empty());
}

// The paper's Fig. 3 case: a foreground point with the background's colour (the uncovered
// background behind the object) must become unknown, and a background point with the
// object's colour likewise; no point may switch sets.
TEST(Classify, GmmRefinementRemovesPlantedMislabelledPoints) {
  cv::RNG rng(1);
  std::vector<cv::Vec3f> colours;
  std::vector<FeatureLabel> labels;
  for (int i = 0; i < 40; ++i) {  // red object
    colours.emplace_back(rng.uniform(20.f, 40.f), rng.uniform(20.f, 40.f), rng.uniform(200.f, 230.f));
    labels.push_back(FeatureLabel::kForeground);
  }
  for (int i = 0; i < 80; ++i) {  // green-blue background
    colours.emplace_back(rng.uniform(150.f, 200.f), rng.uniform(120.f, 160.f), rng.uniform(20.f, 50.f));
    labels.push_back(FeatureLabel::kBackground);
  }
  colours.emplace_back(175, 140, 35);  // background colour labelled foreground
  labels.push_back(FeatureLabel::kForeground);
  colours.emplace_back(30, 30, 215);   // object colour labelled background
  labels.push_back(FeatureLabel::kBackground);
  const size_t n = labels.size();
  refineByColour(colours, 5, &labels);
  EXPECT_EQ(labels[n - 2], FeatureLabel::kUnknown);
  EXPECT_EQ(labels[n - 1], FeatureLabel::kUnknown);
  EXPECT_EQ(std::count(labels.begin(), labels.end(), FeatureLabel::kForeground), 40);
  EXPECT_EQ(std::count(labels.begin(), labels.end(), FeatureLabel::kBackground), 80);
}

TEST(Classify, RefinementNeedsBothSets) {
  std::vector<FeatureLabel> labels(3, FeatureLabel::kForeground);
  refineByColour({{1, 2, 3}, {4, 5, 6}, {200, 0, 0}}, 2, &labels);
  EXPECT_EQ(std::count(labels.begin(), labels.end(), FeatureLabel::kForeground), 3);
}

}  // namespace
}  // namespace movseg
