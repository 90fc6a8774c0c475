// The RANSAC loop of motion/ransac.h and its parts: the estimators, the spread sampler and the
// coverage support measure, each against known answers.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "motion/model.h"
#include "motion/ransac.h"

namespace movseg {
namespace {

const cv::Size kImage(320, 240);
const cv::Matx33d kAffine(1.02, -0.05, 3.5, 0.04, 0.99, -2.0, 0, 0, 1);
const cv::Matx33d kHomography(1.01, 0.02, 4.0, -0.03, 0.98, 1.5, 2e-4, -1e-4, 1);

std::vector<cv::Point2f> spreadPoints(int count, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Point2f> points;
  for (int i = 0; i < count; ++i) {
    points.emplace_back(rng.uniform(0.f, 320.f), rng.uniform(0.f, 240.f));
  }
  return points;
}

std::vector<cv::Point2f> mapped(const cv::Matx33d& model, const std::vector<cv::Point2f>& x) {
  std::vector<cv::Point2f> y;
  for (const cv::Point2f& p : x) y.push_back(applyModel(model, p));
  return y;
}

double maxResidual(const std::vector<double>& residuals) {
  return *std::max_element(residuals.begin(), residuals.end());
}

TEST(Estimators, AffineIsExactOnThreePointsAndRefusesCollinearOnes) {
  const std::vector<cv::Point2f> x{{10, 20}, {300, 40}, {150, 220}};
  cv::Matx33d model;
  ASSERT_TRUE(AffineEstimator::estimate(x, mapped(kAffine, x), &model));
  EXPECT_LT(cv::norm(model - kAffine, cv::NORM_INF), 1e-6);
  std::vector<double> residuals;
  AffineEstimator::residuals(x, mapped(kAffine, x), model, &residuals);
  EXPECT_LT(maxResidual(residuals), 1e-8);
  const std::vector<cv::Point2f> line{{0, 0}, {10, 10}, {20, 20}};
  EXPECT_FALSE(AffineEstimator::estimate(line, line, &model));
}

TEST(Estimators, HomographyIsExactOnFourPointsAndFitsManyByLeastSquares) {
  const std::vector<cv::Point2f> x{{10, 20}, {300, 30}, {290, 220}, {20, 230}};
  cv::Matx33d model;
  ASSERT_TRUE(HomographyEstimator::estimate(x, mapped(kHomography, x), &model));
  EXPECT_LT(cv::norm(model - kHomography, cv::NORM_INF), 1e-5);  // float points
  const std::vector<cv::Point2f> many = spreadPoints(50, 3);
  ASSERT_TRUE(HomographyEstimator::estimate(many, mapped(kHomography, many), &model));
  std::vector<double> residuals;
  HomographyEstimator::residuals(many, mapped(kHomography, many), model, &residuals);
  EXPECT_LT(maxResidual(residuals), 1e-4);
  const std::vector<cv::Point2f> collinear{{0, 0}, {10, 10}, {20, 20}, {100, 5}};
  EXPECT_FALSE(HomographyEstimator::estimate(collinear, mapped(kHomography, collinear), &model));
}

// The least-squares fit is a normalised DLT (algebraic error), not OpenCV's Levenberg-Marquardt
// refinement (geometric error): on inliers with half a pixel of noise the two models put every
// pixel of the image within a twentieth of a pixel of each other.
TEST(Estimators, HomographyLeastSquaresAgreesWithOpenCvsRefinedFitOnNoisyPoints) {
  const std::vector<cv::Point2f> x = spreadPoints(300, 5);
  std::vector<cv::Point2f> y = mapped(kHomography, x);
  cv::RNG rng(11);
  for (cv::Point2f& p : y) p += cv::Point2f(rng.gaussian(0.5), rng.gaussian(0.5));
  cv::Matx33d ours;
  ASSERT_TRUE(HomographyEstimator::estimate(x, y, &ours));
  const cv::Matx33d opencv(cv::findHomography(x, y, 0));
  double largest = 0;
  for (int v = 0; v <= kImage.height; v += 20) {
    for (int u = 0; u <= kImage.width; u += 20) {
      const cv::Point2f p(static_cast<float>(u), static_cast<float>(v));
      largest = std::max(largest, cv::norm(applyModel(ours, p) - applyModel(opencv, p)));
    }
  }
  EXPECT_LT(largest, 0.05);
  EXPECT_GT(largest, 0.0);  // they are different fits
}

TEST(Estimators, ResidualsAreSquaredTransferErrors) {
  const std::vector<cv::Point2f> x{{0, 0}, {10, 5}}, y{{3, 4}, {10, 5}};
  std::vector<double> residuals;
  AffineEstimator::residuals(x, y, cv::Matx33d::eye(), &residuals);
  EXPECT_EQ(residuals, (std::vector<double>{25.0, 0.0}));
}

TEST(SpreadSampler, DrawsEachSampleFromDistinctCells) {
  const std::vector<cv::Point2f> points = spreadPoints(200, 1);
  const SpreadSampler sampler(points, kImage, 3);
  cv::RNG rng(5);
  std::vector<int> sample;
  auto cell = [&](int i) {
    return static_cast<int>(points[i].x / (320.f / 3)) + 3 * static_cast<int>(points[i].y / 80.f);
  };
  for (int trial = 0; trial < 200; ++trial) {
    ASSERT_TRUE(sampler.sample(4, rng, &sample));
    std::set<int> cells;
    for (int i : sample) cells.insert(cell(i));
    EXPECT_EQ(cells.size(), 4u) << "trial " << trial;
  }
}

TEST(SpreadSampler, FallsBackToDistinctPointsWhenTooFewCellsAreOccupied) {
  const std::vector<cv::Point2f> corner{{1, 1}, {2, 3}, {5, 2}, {4, 4}};
  const SpreadSampler sampler(corner, kImage, 3);
  cv::RNG rng(7);
  std::vector<int> sample;
  for (int trial = 0; trial < 50; ++trial) {
    ASSERT_TRUE(sampler.sample(3, rng, &sample));
    EXPECT_EQ(std::set<int>(sample.begin(), sample.end()).size(), 3u);
  }
  EXPECT_FALSE(sampler.sample(5, rng, &sample));
}

TEST(CoverageSupport, SpreadInliersBeatMoreInliersInOneCorner) {
  std::vector<cv::Point2f> points = spreadPoints(20, 2);  // 0..19: over the image
  for (int i = 0; i < 40; ++i) points.emplace_back(5.f + i % 7, 5.f + i / 7);  // 20..59: a corner
  const CoverageSupportMeasurer measurer(points, kImage);
  std::vector<double> spread(points.size(), 100.0), corner(points.size(), 100.0);
  std::fill(spread.begin(), spread.begin() + 20, 0.0);
  std::fill(corner.begin() + 20, corner.end(), 0.0);
  const auto a = measurer.evaluate(spread, 1.0), b = measurer.evaluate(corner, 1.0);
  EXPECT_EQ(a.num_inliers, 20);
  EXPECT_EQ(b.num_inliers, 40);
  EXPECT_TRUE(CoverageSupportMeasurer::better(a, b));
  EXPECT_FALSE(CoverageSupportMeasurer::better(b, a));
  EXPECT_FALSE(CoverageSupportMeasurer::better(a, a));
}

// 60 % of the correspondences follow the model, 40 % are far off.
struct Outliers {
  std::vector<cv::Point2f> x, y;
  std::vector<char> inlier;
};

Outliers withOutliers(const cv::Matx33d& model, int count, std::uint64_t seed) {
  Outliers data;
  data.x = spreadPoints(count, seed);
  data.y = mapped(model, data.x);
  cv::RNG rng(seed + 100);
  for (int i = 0; i < count; ++i) {
    const bool inlier = i % 5 < 3;
    data.inlier.push_back(inlier);
    if (!inlier) data.y[i] += cv::Point2f(rng.uniform(8.f, 40.f), rng.uniform(-40.f, -8.f));
  }
  return data;
}

TEST(Ransac, RecoversTheModelAndExactlyItsInliers) {
  const Outliers data = withOutliers(kAffine, 150, 4);
  cv::RNG rng(1);
  const auto report = Ransac<AffineEstimator>(RansacOptions()).estimate(data.x, data.y, kImage, rng);
  ASSERT_TRUE(report.success);
  EXPECT_LT(cv::norm(report.model - kAffine, cv::NORM_INF), 1e-4);
  EXPECT_EQ(report.inlier_mask, data.inlier);
  EXPECT_EQ(report.num_inliers, 90);
  EXPECT_GT(report.trials, 0);
  EXPECT_LT(report.trials, RansacOptions().max_trials);  // adaptive: 60 % inliers need ~19
}

TEST(Ransac, HomographyThroughTheSameLoop) {
  const Outliers data = withOutliers(kHomography, 150, 6);
  cv::RNG rng(2);
  const auto report =
      Ransac<HomographyEstimator>(RansacOptions()).estimate(data.x, data.y, kImage, rng);
  ASSERT_TRUE(report.success);
  EXPECT_EQ(report.inlier_mask, data.inlier);
}

// The initial model is scored first and no sample can beat the truth. (It does not shorten the
// loop: the trial count adapts to sampled hypotheses only, as the paper's reproduction has it.)
TEST(Ransac, AWarmStartAtTheTruthIsKept) {
  const Outliers data = withOutliers(kAffine, 100, 8);
  cv::RNG rng(3);
  const auto report = Ransac<AffineEstimator>(RansacOptions())
                          .estimate(data.x, data.y, kImage, rng, &kAffine);
  ASSERT_TRUE(report.success);
  EXPECT_LT(cv::norm(report.model - kAffine, cv::NORM_INF), 1e-4);
  EXPECT_EQ(report.inlier_mask, data.inlier);
}

// Fewer correspondences than a minimal sample fail; unrelated ones leave only the sample itself
// as inliers.
TEST(Ransac, FailsWithTooFewAndFindsNothingInUnrelatedCorrespondences) {
  cv::RNG rng(4);
  const std::vector<cv::Point2f> two{{1, 1}, {50, 80}};
  const auto few = Ransac<AffineEstimator>(RansacOptions()).estimate(two, two, kImage, rng);
  EXPECT_FALSE(few.success);
  EXPECT_EQ(few.trials, 0);
  const std::vector<cv::Point2f> x = spreadPoints(30, 9), y = spreadPoints(30, 10);
  RansacOptions options;
  options.max_error = 0.01;
  const auto unrelated = Ransac<AffineEstimator>(options).estimate(x, y, kImage, rng);
  EXPECT_LE(unrelated.num_inliers, AffineEstimator::kMinNumSamples);
  EXPECT_EQ(unrelated.trials, options.max_trials);
}

// A new model is one more Estimator class: a pure translation, for instance.
struct TranslationEstimator {
  using Model = cv::Point2f;
  static constexpr int kMinNumSamples = 1;
  static bool estimate(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                       Model* model) {
    cv::Point2f sum(0, 0);
    for (size_t i = 0; i < x.size(); ++i) sum += y[i] - x[i];
    *model = sum / static_cast<float>(x.size());
    return !x.empty();
  }
  static void residuals(const std::vector<cv::Point2f>& x, const std::vector<cv::Point2f>& y,
                        const Model& model, std::vector<double>* residuals) {
    residuals->clear();
    for (size_t i = 0; i < x.size(); ++i) {
      const cv::Point2f d = x[i] + model - y[i];
      residuals->push_back(d.dot(d));
    }
  }
};

TEST(Ransac, ANewEstimatorPlugsIntoTheSameLoop) {
  const Outliers data = withOutliers(cv::Matx33d(1, 0, 7, 0, 1, -3, 0, 0, 1), 100, 11);
  cv::RNG rng(5);
  const auto report =
      Ransac<TranslationEstimator>(RansacOptions()).estimate(data.x, data.y, kImage, rng);
  ASSERT_TRUE(report.success);
  EXPECT_NEAR(report.model.x, 7, 1e-3);
  EXPECT_NEAR(report.model.y, -3, 1e-3);
  EXPECT_EQ(report.inlier_mask, data.inlier);
}

// Plane + parallax: static points are displaced along the lines through the epipole (by a
// depth-dependent amount, outward or inward), movers across them.
TEST(Estimators, EpipoleFromParallaxThroughTheLoopLeavesOutTheMovers) {
  const cv::Vec3d epipole(200, 90, 1);
  cv::RNG rng(3);
  std::vector<cv::Point2f> x = spreadPoints(120, 21), y;
  std::vector<char> is_static;
  for (const cv::Point2f& p : x) {
    const cv::Point2f away = p - cv::Point2f(200, 90);
    const bool mover = y.size() % 4 == 0;  // a quarter move sideways to their line
    const float depth = rng.uniform(0.02f, 0.1f) * (rng.uniform(0, 2) ? 1.f : -1.f);
    const cv::Point2f across = cv::Point2f(-away.y, away.x) * (3 / std::hypot(away.x, away.y));
    y.push_back(mover ? p + across : p + away * depth);
    is_static.push_back(!mover);
  }
  const auto report = Ransac<EpipoleEstimator>(RansacOptions()).estimate(x, y, kImage, rng);
  ASSERT_TRUE(report.success);
  EXPECT_NEAR(report.model[0] / report.model[2], 200, 0.5);
  EXPECT_NEAR(report.model[1] / report.model[2], 90, 0.5);
  EXPECT_EQ(report.inlier_mask, is_static);
  EXPECT_NEAR(EpipoleEstimator::offLine({100, 90}, {90, 90}, epipole), 0, 1e-9);  // along
  EXPECT_NEAR(EpipoleEstimator::offLine({100, 90}, {100, 84}, epipole), 6, 1e-9);  // across
}

// A camera translating sideways puts the epipole at infinity: parallel displacements.
TEST(Estimators, EpipoleAtInfinityForParallelDisplacements) {
  const std::vector<cv::Point2f> x{{10, 20}, {200, 150}}, y{{14, 20}, {201, 150}};
  cv::Vec3d e;
  ASSERT_TRUE(EpipoleEstimator::estimate(x, y, &e));
  EXPECT_NEAR(e[2], 0, 1e-9);
  EXPECT_NEAR(EpipoleEstimator::offLine({50, 60}, {47, 60}, e), 0, 1e-9);
  EXPECT_NEAR(EpipoleEstimator::offLine({50, 60}, {50, 62}, e), 2, 1e-9);
  EXPECT_FALSE(EpipoleEstimator::estimate({{0, 0}, {10, 0}}, {{5, 0}, {20, 0}}, &e));  // one line
}

// Random symmetric positive semi-definite matrices, as the least-squares fits' are.
template <int n>
cv::Matx<double, n, n> randomScatter(cv::RNG& rng) {
  cv::Matx<double, n, n> m = cv::Matx<double, n, n>::zeros();
  for (int k = rng.uniform(n - 1, 3 * n); k > 0; --k) {
    cv::Vec<double, n> row;
    for (int i = 0; i < n; ++i) row[i] = rng.gaussian(rng.uniform(0.01, 100.0));
    m += row * row.t();
  }
  return m;
}

template <int n>
void expectCvEigensSmallestVector(cv::RNG& rng) {
  for (int trial = 0; trial < 2000; ++trial) {
    const cv::Matx<double, n, n> m = randomScatter<n>(rng);
    cv::Matx<double, n, 1> values;
    cv::Matx<double, n, n> vectors;
    ASSERT_TRUE(cv::eigen(m, values, vectors));
    cv::Vec<double, n> ours;
    ASSERT_TRUE(smallestEigenvector(m, &ours));
    for (int i = 0; i < n; ++i) ASSERT_EQ(ours[i], vectors(n - 1, i)) << trial;  // to the bit
  }
}

TEST(Estimators, SmallestEigenvectorIsCvEigensToTheBit) {
  cv::RNG rng(7);
  expectCvEigensSmallestVector<3>(rng);
  expectCvEigensSmallestVector<9>(rng);
}

TEST(Estimators, HomographyThroughFourPointsIsGetPerspectiveTransformsToTheBit) {
  cv::RNG rng(8);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::vector<cv::Point2f> x = spreadPoints(4, static_cast<std::uint64_t>(trial) + 1);
    std::vector<cv::Point2f> y;
    for (const cv::Point2f& p : x) {
      const float dx = rng.uniform(-5.f, 5.f), dy = rng.uniform(-5.f, 5.f);
      y.push_back(p + cv::Point2f(dx, dy));
    }
    const cv::Matx33d opencv(cv::getPerspectiveTransform(x, y));
    // estimate() refuses a model that flips or collapses the plane (determinant <= 1e-6), as
    // OpenCV's is for 205 of these samples.
    const bool valid = cv::determinant(opencv) > 1e-6;
    cv::Matx33d ours;
    ASSERT_EQ(HomographyEstimator::estimate(x, y, &ours), valid) << trial;
    if (!valid) continue;
    for (int i = 0; i < 9; ++i) ASSERT_EQ(ours.val[i], opencv.val[i]) << trial;
    ++compared;
  }
  EXPECT_EQ(compared, 2000 - 205);
}

TEST(RansacOptions, CheckRejectsEachOptionOutOfRange) {
  EXPECT_NO_THROW(RansacOptions().check());
  for (int field = 0; field < 4; ++field) {
    RansacOptions options;
    if (field == 0) options.max_trials = 0;
    if (field == 1) options.max_error = -1;
    if (field == 2) options.confidence = 1;
    if (field == 3) options.sample_grid = 0;
    EXPECT_THROW(options.check(), std::invalid_argument) << field;
    EXPECT_THROW(Ransac<AffineEstimator>{options}, std::invalid_argument) << field;
  }
}

}  // namespace
}  // namespace movseg
