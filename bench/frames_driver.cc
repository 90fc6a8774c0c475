// build/bench/movseg_frames FOLDER [N] [name=value ...]: runs a Segmenter over the first N images
// of FOLDER (sorted by name), with parameters set by name, and prints the mean stage times.
// It links only the library and OpenCV's image codecs — no FFmpeg — so that it runs under
// valgrind: `bench/instructions.sh` counts its instructions, a figure that does not depend on
// what else the machine is doing.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "image_files.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FOLDER [N] [name=value ...]\n", argv[0]);
    return 2;
  }
  cv::setNumThreads(1);
  const std::vector<std::string> files = imagesIn(argv[1]);
  const size_t count = std::min(files.size(), argc > 2 ? std::stoul(argv[2]) : files.size());
  movseg::Params params;
  for (int i = 3; i < argc; ++i) {
    const std::string assignment = argv[i];
    const size_t eq = assignment.find('=');
    movseg::setParam(&params, assignment.substr(0, eq), assignment.substr(eq + 1));
  }
  movseg::Segmenter segmenter(params);
  movseg::Diagnostics sum;
  for (size_t i = 0; i < count; ++i) {
    const movseg::Diagnostics d = segmenter.process(cv::imread(files[i])).diagnostics;
    sum.prepare_ms += d.prepare_ms;
    sum.motion_ms += d.motion_ms;
    sum.classify_ms += d.classify_ms;
    sum.cut_ms += d.cut_ms;
    sum.total_ms += d.total_ms;
  }
  const double n = static_cast<double>(std::max<size_t>(count, 1));
  std::printf("%zu frames, mean ms: prepare %.2f motion %.2f classify %.2f cut %.2f total %.2f\n",
              count, sum.prepare_ms / n, sum.motion_ms / n, sum.classify_ms / n, sum.cut_ms / n,
              sum.total_ms / n);
  return 0;
}
