#include "methods/method.h"

#include <functional>
#include <stdexcept>
#include <utility>

#include "methods/baselines.h"

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

using Factory = std::function<std::unique_ptr<Method>(const Params&)>;

const std::vector<std::pair<std::string, Factory>>& registry() {
  static const std::vector<std::pair<std::string, Factory>> methods{
      {"paper", [](const Params& p) { return std::make_unique<PaperMethod>(p); }},
      {"diff", makeDiffMethod},
      {"mog2", makeMog2Method},
      {"mog2-comp", makeCompensatedMog2Method},
  };
  return methods;
}

}  // namespace

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

std::unique_ptr<Method> makeMethod(const std::string& name, const Params& params) {
  for (const auto& [known, factory] : registry()) {
    if (known == name) return factory(params);
  }
  throw std::invalid_argument("unknown method '" + name + "'");
}

}  // namespace movseg
