#include "accuracy_fixture.h"

#include <opencv2/imgproc.hpp>

#include "movseg/segmenter.h"

namespace movseg::test {

void toGrey(int /*t*/, cv::Mat* frame) { cv::cvtColor(*frame, *frame, cv::COLOR_BGR2GRAY); }

double meanIou(const SynthOptions& clip, const Params& params, const FrameChange& change,
               const cv::Mat& ignored) {
  const SynthSequence sequence(clip);
  Segmenter segmenter(params);
  segmenter.setIgnoredRegion(ignored);
  double sum = 0;
  int counted = 0;
  for (int t = 0; t < sequence.size(); ++t) {
    SynthFrame f = sequence.frame(t);
    if (change) change(t, &f.frame);
    const cv::Mat mask = segmenter.process(f.frame).mask;
    if (t == 0) continue;  // no previous frame, no motion
    if (!ignored.empty()) f.mask.setTo(0, ignored);
    const double uni = cv::countNonZero(mask | f.mask);
    sum += uni > 0 ? cv::countNonZero(mask & f.mask) / uni : 1.0;
    ++counted;
  }
  return sum / counted;
}

}  // namespace movseg::test
