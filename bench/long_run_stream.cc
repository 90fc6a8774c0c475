#include "long_run_stream.h"

#include <chrono>
#include <fstream>
#include <string>
#include <vector>

#include "movseg/segmenter.h"
#include "synth/synth.h"

namespace movseg {
namespace {

std::vector<cv::Mat> cachedFrames(int count) {
  SynthOptions options;
  options.frames = count;
  const SynthSequence sequence(options);
  std::vector<cv::Mat> frames;
  for (int t = 0; t < count; ++t) frames.push_back(sequence.frame(t).frame);
  return frames;
}

// 0, 1, ..., n-1, n-2, ..., 1, 0, 1, ...
int pingPong(int i, int n) {
  if (n < 2) return 0;
  const int period = 2 * (n - 1), t = i % period;
  return t < n ? t : period - t;
}

}  // namespace

long residentKib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kib = -1;
      status >> kib;
      return kib;
    }
    status.ignore(1 << 16, '\n');
  }
  return -1;
}

LongRunReport runLongStream(int frames, int warmup, int cached,
                            const std::function<void(int, long)>& progress) {
  const std::vector<cv::Mat> stream = cachedFrames(cached);
  Segmenter segmenter;
  LongRunReport report;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    const cv::Mat& frame = stream[static_cast<size_t>(pingPong(i, cached))];
    report.motion_fallbacks += segmenter.process(frame).diagnostics.motion_fallback;
    if (i + 1 == warmup) report.warm_kib = residentKib();
    if (progress && (i + 1) % 1000 == 0) progress(i + 1, residentKib());
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.frames = frames;
  report.end_kib = residentKib();
  return report;
}

}  // namespace movseg
