#include "flow/dense_flow.h"

#include <algorithm>

namespace movseg {
namespace {

// DIS matches 8x8 patches and refuses images under 12 pixels a side; a frame smaller than two
// patches a side carries no measurable motion.
constexpr int kMinSide = 16;

bool measurable(const cv::Size& size) { return std::min(size.width, size.height) >= kMinSide; }

}  // namespace

DenseFlow::DenseFlow(int finest_scale)
    : dis_(cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_FAST)) {
  dis_->setFinestScale(finest_scale);
  // No variational refinement: it costs as much as the patch search (18M of 40M instructions per
  // pair at 320x180) and buys nothing measurable downstream — DAVIS J 0.579 with it, 0.575
  // without (F 0.537 both), synthetic sets as good or better (docs/design.md, "Speed of dense").
  dis_->setVariationalRefinementIterations(0);
}

void DenseFlow::next(const cv::Mat& grey, cv::Mat* flow) {
  CV_Assert(grey.type() == CV_8UC1 && grey.isContinuous());
  if (previous_grey_.size() != grey.size() || !measurable(grey.size())) {
    flow->release();
  } else {
    // DIS starts from the flow it is given (motion changes little from one pair to the next);
    // the first pair starts from rest.
    if (previous_flow_.empty()) {
      flow->create(grey.size(), CV_32FC2);
      flow->setTo(cv::Scalar::all(0));
    } else {
      previous_flow_.copyTo(*flow);
    }
    dis_->calc(grey, previous_grey_, *flow);
  }
  previous_grey_ = grey;
  previous_flow_ = *flow;
}

void DenseFlow::reset() {
  previous_grey_.release();
  previous_flow_.release();
}

}  // namespace movseg
