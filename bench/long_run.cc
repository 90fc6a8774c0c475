// movseg_long_run [FRAMES [MAX_GROWTH_MIB]]: FRAMES (20000) synthetic 320x240 frames through one
// Segmenter; prints resident memory after the warm-up and at the end, and exits 1 when it grew
// by more than MAX_GROWTH_MIB (4). `make long-run` builds and runs it.
#include <cstdio>
#include <cstdlib>

#include <opencv2/core/utility.hpp>

#include "long_run_stream.h"

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 20000;
  const double max_growth_mib = argc > 2 ? std::atof(argv[2]) : 4.0;
  constexpr int kWarmup = 200, kCached = 300;
  if (frames < kWarmup) {
    std::fprintf(stderr, "movseg_long_run: FRAMES must be at least %d\n", kWarmup);
    return 2;
  }
  cv::setNumThreads(1);  // as the CLI runs
  const movseg::LongRunReport r =
      movseg::runLongStream(frames, kWarmup, kCached, [](int done, long kib) {
        std::printf("%6d frames  RSS %.1f MiB\n", done, kib / 1024.0);
        std::fflush(stdout);
      });
  const double growth_mib = (r.end_kib - r.warm_kib) / 1024.0;
  std::printf("%d frames in %.1f s (%.1f fps), %d alignment fallbacks; RSS after %d frames "
              "%.1f MiB, at the end %.1f MiB: %+.2f MiB (limit %.1f)\n",
              r.frames, r.seconds, r.frames / r.seconds, r.motion_fallbacks, kWarmup,
              r.warm_kib / 1024.0, r.end_kib / 1024.0, growth_mib, max_growth_mib);
  return growth_mib > max_growth_mib ? 1 : 0;
}
