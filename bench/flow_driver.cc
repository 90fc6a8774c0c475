// build/bench/movseg_flow FOLDER N opencv|movseg: the dense flow of the first N images of FOLDER
// (sorted by name, read as grey), from each frame to the previous one as DenseFlow computes it
// (each pair from the previous pair's flow), by OpenCV's cv::DISOpticalFlow at movseg's settings
// or by movseg's DisFlow. It links only the library and OpenCV's image codecs, so that it runs
// under valgrind: `bench/flow_instructions.sh` counts the instructions of flowPair, a figure that
// does not depend on what else the machine is doing.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "flow/dense_flow.h"
#include "image_files.h"
#include "movseg/params.h"
#include "opencv_dense_flow.h"

namespace {

// One pair, not inlined: what the instruction count is taken of.
template <class Flow>
__attribute__((noinline)) void flowPair(Flow* flow, const cv::Mat& grey, cv::Mat* out) {
  flow->next(grey, out);
}

template <class Flow>
void run(Flow* flow, const std::vector<cv::Mat>& frames) {
  cv::Mat flows[2];  // two in flight, as the pipeline keeps them
  for (size_t t = 0; t < frames.size(); ++t) flowPair(flow, frames[t], &flows[t % 2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s FOLDER N opencv|movseg\n", argv[0]);
    return 2;
  }
  cv::setNumThreads(1);
  std::vector<std::string> files = imagesIn(argv[1]);
  files.resize(std::min(files.size(), std::stoul(argv[2])));
  std::vector<cv::Mat> frames;
  for (const std::string& file : files) frames.push_back(cv::imread(file, cv::IMREAD_GRAYSCALE));
  const int finest = movseg::Params().flow_finest_scale;
  const std::string impl = argv[3];
  if (impl == "opencv") {
    movseg::OpenCvDenseFlow flow(finest);
    run(&flow, frames);
  } else if (impl == "movseg") {
    movseg::DenseFlow flow(finest);
    run(&flow, frames);
  } else {
    std::fprintf(stderr, "unknown implementation %s\n", impl.c_str());
    return 2;
  }
  std::printf("%zu frames, %zu pairs (%s)\n", frames.size(), frames.size() - 1, impl.c_str());
  return 0;
}
