// A long synthetic camera stream through one Segmenter, with the process's resident memory
// before and after: the benchmark long_run.cc and the short test in tests/reliability/.
#pragma once

#include <functional>

namespace movseg {

// Resident set size of this process (VmRSS in /proc/self/status), in KiB; -1 when unknown.
long residentKib();

struct LongRunReport {
  int frames = 0;
  long warm_kib = 0;  // RSS after the warm-up frames
  long end_kib = 0;   // RSS after the last frame
  double seconds = 0;
  int motion_fallbacks = 0;
};

// Pushes `frames` 320x240 frames through one Segmenter: the first `cached` frames of a
// SynthSequence, generated once, played forwards then backwards again and again, so that the
// camera never cuts. RSS is read after `warmup` frames and at the end; `progress` (if set) is
// told the frame count and RSS every 1000 frames.
LongRunReport runLongStream(int frames, int warmup, int cached,
                            const std::function<void(int, long)>& progress = {});

}  // namespace movseg
