#include <stdexcept>
#include <string>

#include "movseg/params.h"

namespace movseg {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("invalid parameter: " + what);
}

}  // namespace

void Params::check() const {
  require(alignment_width >= 0, "alignment_width must be >= 0 (0 = native size)");
  require(segmentation_width >= 0, "segmentation_width must be >= 0 (0 = native size)");
  require(max_corners >= 0, "max_corners must be >= 0");
  require(edge_cell >= 2, "edge_cell must be >= 2");
  require(max_tracked_features >= 8, "max_tracked_features must be >= 8");
  require(lk_window >= 3 && lk_window % 2 == 1, "lk_window must be odd and >= 3");
  require(lk_levels >= 0 && lk_levels <= 8, "lk_levels must be in [0, 8]");
  require(zncc_window >= 3 && zncc_window % 2 == 1, "zncc_window must be odd and >= 3");
  require(ransac_iterations >= 1, "ransac_iterations must be >= 1");
  require(ransac_threshold > 0, "ransac_threshold must be > 0");
  require(ransac_grid >= 1 && ransac_grid <= 16, "ransac_grid must be in [1, 16]");
  require(max_outer_iterations >= 1, "max_outer_iterations must be >= 1");
  require(lambda >= 0, "lambda must be >= 0");
  require(lambda_residual_factor >= 0, "lambda_residual_factor must be >= 0");
  require(difference_blur >= 0 && difference_blur <= 20, "difference_blur must be in [0, 20]");
  require(gmm_clusters >= 1, "gmm_clusters (K) must be >= 1");
  require(cut_weight >= 0, "cut_weight must be >= 0");
  require(cut_band >= 0, "cut_band must be >= 0 (0 = whole image)");
  require(geodesic_gamma >= 0, "geodesic_gamma must be >= 0");
}

}  // namespace movseg
