#include <stdexcept>

#include <gtest/gtest.h>

#include "movseg/params.h"

namespace movseg {
namespace {

TEST(Params, DefaultsAreValid) { EXPECT_NO_THROW(Params().check()); }

TEST(Params, OutOfRangeValuesNameTheParameter) {
  Params p;
  p.gmm_clusters = 0;
  try {
    p.check();
    FAIL() << "K = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gmm_clusters"), std::string::npos);
  }
  p = Params();
  p.lambda = -1;
  EXPECT_THROW(p.check(), std::invalid_argument);
  p = Params();
  p.zncc_window = 10;
  EXPECT_THROW(p.check(), std::invalid_argument);
  p = Params();
  p.alignment_width = -5;
  EXPECT_THROW(p.check(), std::invalid_argument);
}

}  // namespace
}  // namespace movseg
