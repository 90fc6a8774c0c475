#include "pipelines/pipeline.h"

#include <stdexcept>

namespace movseg {

std::unique_ptr<Pipeline> makePipeline(const Params& params) {
  switch (params.method) {
    case Method::kPaper: return makePaperPipeline(params);
    case Method::kDiff: return makeDiffPipeline(params);
    case Method::kMog2: return makeMog2Pipeline(params);
    case Method::kMog2Compensated: return makeCompensatedMog2Pipeline(params);
    case Method::kDense: return makeDensePipeline(params);
  }
  throw std::invalid_argument("unknown method");
}

}  // namespace movseg
