// Segmentation methods behind one interface, so the CLI, the evaluation and the benchmarks
// treat the paper's pipeline and the baselines alike. Adding a method is one small file plus a
// line in method.cc.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg {

class Method {
 public:
  virtual ~Method() = default;
  // Same contract as Segmenter::process: any supported frame in, a 0/255 mask of its size out.
  virtual Result process(const cv::Mat& frame) = 0;
};

// The registered names, in the order tables show them.
std::vector<std::string> methodNames();

// Throws std::invalid_argument for an unknown name or invalid parameters.
std::unique_ptr<Method> makeMethod(const std::string& name, const Params& params);

}  // namespace movseg
