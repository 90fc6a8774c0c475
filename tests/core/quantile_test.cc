// Order statistics: the element at a fraction of the sorted values without interpolation, and
// the median of a histogram of 8-bit levels, worked by hand.
#include "core/quantile.h"

#include <gtest/gtest.h>

namespace movseg {
namespace {

TEST(Quantile, IsTheElementAtTheFractionRoundedDown) {
  const std::vector<float> values{5, 1, 4, 2, 3};
  const auto at = [&](double q) {
    std::vector<float> copy = values;
    return quantile(&copy, q);
  };
  EXPECT_EQ(at(0.0), 1.f);
  EXPECT_EQ(at(0.5), 3.f);   // index 2 of 0..4
  EXPECT_EQ(at(0.9), 4.f);   // index 3.6, rounded down: no interpolation
  EXPECT_EQ(at(1.0), 5.f);
  std::vector<float> one{7};
  EXPECT_EQ(quantile(&one, 0.95), 7.f);
}

TEST(Median, IsTheLowestLevelWithMoreThanHalfAtOrBelowIt) {
  LevelHistogram h{};
  h[3] = 1;
  h[7] = 1;
  h[9] = 1;
  EXPECT_EQ(median(h), 7);
  h[9] = 0;  // two values: half of them at or below 3 is not more than half
  EXPECT_EQ(median(h), 7);
  h[3] = 5;
  EXPECT_EQ(median(h), 3);
  EXPECT_EQ(median(LevelHistogram{}), 255);  // counts none
}

}  // namespace
}  // namespace movseg
