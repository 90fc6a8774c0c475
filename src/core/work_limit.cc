#include "core/work_limit.h"

namespace movseg {

WorkLimit withinWorkLimit(const Params& params, cv::Size) {
  return {params, false};
}

}  // namespace movseg
