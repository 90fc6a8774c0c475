#include "methods/method.h"

#include <stdexcept>

namespace movseg {
namespace {

// `paper`: the full pipeline of the paper (Segmenter).
class PaperMethod : public Method {
 public:
  explicit PaperMethod(const Params& params) : segmenter_(params) {}
  Result process(const cv::Mat& frame) override { return segmenter_.process(frame); }

 private:
  Segmenter segmenter_;
};

}  // namespace

std::vector<std::string> methodNames() { return {"paper"}; }

std::unique_ptr<Method> makeMethod(const std::string& name, const Params& params) {
  if (name == "paper") return std::make_unique<PaperMethod>(params);
  throw std::invalid_argument("unknown method '" + name + "'");
}

}  // namespace movseg
