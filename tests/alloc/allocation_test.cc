// Allocations per frame in the steady state of Segmenter::process, for a fixed frame size.
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "alloc/counting_malloc.h"

namespace movseg {
namespace {

TEST(Allocations, TheCounterSeesNewVectorsAndOpenCvBuffers) {
  cv::Mat image(48, 64, CV_8UC3);  // OpenCV's first allocation sets up more than the buffer
  std::int64_t after_int = 0, after_vector = 0, after_mat = 0, after_reuse = 0;
  {
    test::CountAllocations counter;
    auto one = std::make_unique<int>(1);
    after_int = counter.count();
    std::vector<double> values(1000);
    after_vector = counter.count();
    image.create(480, 640, CV_8UC3);
    after_mat = counter.count();
    image.create(480, 640, CV_8UC3);  // the same size and type: reused
    after_reuse = counter.count();
  }
  EXPECT_EQ(after_int, 1);
  EXPECT_EQ(after_vector, 2);
  EXPECT_GT(after_mat, after_vector);
  EXPECT_EQ(after_reuse, after_mat);
}

}  // namespace
}  // namespace movseg
