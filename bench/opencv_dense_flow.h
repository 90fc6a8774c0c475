// The DenseFlow that drove OpenCV's cv::DISOpticalFlow before movseg had its own (flow/dis_flow.h):
// both images given to every call, each pair from the previous pair's flow. The reference the
// benchmarks time DenseFlow against.
#pragma once

#include <opencv2/core.hpp>

#include "flow/dis_flow.h"

namespace movseg {

class OpenCvDenseFlow {
 public:
  explicit OpenCvDenseFlow(int finest_scale) : dis_(openCvDis(finest_scale)) {}

  void next(const cv::Mat& grey, cv::Mat* flow) {
    if (previous_grey_.empty()) {
      flow->release();
    } else {
      if (previous_flow_.empty()) {
        *flow = cv::Mat::zeros(grey.size(), CV_32FC2);
      } else {
        previous_flow_.copyTo(*flow);
      }
      dis_->calc(grey, previous_grey_, *flow);
    }
    previous_grey_ = grey;
    previous_flow_ = *flow;
  }

 private:
  cv::Ptr<cv::DISOpticalFlow> dis_;
  cv::Mat previous_grey_, previous_flow_;
};

}  // namespace movseg
