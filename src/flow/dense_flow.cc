#include "flow/dense_flow.h"

#include <algorithm>

namespace movseg {
namespace {

// DIS matches 8x8 patches; a frame smaller than two patches a side carries no measurable motion.
constexpr int kMinSide = 16;

bool measurable(const cv::Size& size) { return std::min(size.width, size.height) >= kMinSide; }

}  // namespace

// No variational refinement (DisFlow has none): it cost as much as the patch search (18M of 40M
// instructions per pair at 320x180) and bought nothing measurable downstream — DAVIS J 0.579
// with it, 0.575 without (F 0.537 both), synthetic sets as good or better (docs/design.md,
// "Speed of dense").
DenseFlow::DenseFlow(int finest_scale) : dis_(finest_scale) {}

void DenseFlow::next(const cv::Mat& grey, cv::Mat* flow) {
  CV_Assert(grey.type() == CV_8UC1 && grey.isContinuous());
  if (!measurable(grey.size())) {
    flow->release();
    reset();
    return;
  }
  const int current = previous_ == 0 ? 1 : 0;
  dis_.prepare(grey, &frames_[current]);
  if (previous_ < 0 || frames_[previous_].size() != grey.size()) {
    flow->release();
  } else {
    // DIS starts from the flow it is given (motion changes little from one pair to the next);
    // the first pair starts from rest.
    if (previous_flow_.empty()) {
      flow->create(grey.size(), CV_32FC2);
      flow->setTo(cv::Scalar::all(0));
      dis_.calc(frames_[current], frames_[previous_], *flow, flow);
    } else {
      dis_.calc(frames_[current], frames_[previous_], previous_flow_, flow);
    }
  }
  previous_ = current;
  previous_flow_ = *flow;
}

void DenseFlow::reset() {
  previous_ = -1;
  previous_flow_.release();
}

}  // namespace movseg
