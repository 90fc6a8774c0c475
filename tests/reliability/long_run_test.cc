// The short version of `make long-run`: resident memory stays flat over a 600-frame stream.
#include <gtest/gtest.h>

#include "long_run_stream.h"

namespace movseg {
namespace {

// AddressSanitizer's quarantine holds freed memory by design: RSS means nothing there.
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define MOVSEG_ADDRESS_SANITIZER
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define MOVSEG_ADDRESS_SANITIZER
#endif
#endif

TEST(LongRun, ResidentMemoryStaysFlatOver600Frames) {
#ifdef MOVSEG_ADDRESS_SANITIZER
  GTEST_SKIP() << "RSS is not meaningful under AddressSanitizer";
#endif
  const LongRunReport r = runLongStream(600, 100, 60);
  ASSERT_GT(r.warm_kib, 0) << "no /proc/self/status";
  // Measured +4 KiB. A leak of half a kilobyte a frame (250 KiB over these 500 frames) fails
  // here; room is left for one growth of the heap's top (glibc pads it by 128 KiB).
  EXPECT_LT(r.end_kib - r.warm_kib, 256)
      << "RSS " << r.warm_kib << " KiB after 100 frames, " << r.end_kib << " KiB after 600";
  EXPECT_EQ(r.motion_fallbacks, 0);
}

}  // namespace
}  // namespace movseg
