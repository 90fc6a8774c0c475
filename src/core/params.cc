#include <stdexcept>
#include <string>

#include "movseg/params.h"

namespace movseg {
namespace {

// Upper bounds are far beyond any useful setting; they stop a typo (an extra zero, 1e9) from
// turning into a frame that never ends or an allocation that cannot succeed. Every range check
// also rejects NaN and infinity.
constexpr int kMaxWidth = 16384;
constexpr int kMaxWindow = 101;
constexpr double kMaxDifference = 255.0 * 255.0;  // d of eq. (4) never exceeds it

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("invalid parameter: " + what);
}

bool oddWindow(int side) { return side >= 3 && side <= kMaxWindow && side % 2 == 1; }

}  // namespace

void Params::check() const {
  require(alignment_width >= 0 && alignment_width <= kMaxWidth,
          "alignment_width must be in [0, 16384] (0 = native size)");
  require(segmentation_width >= 0 && segmentation_width <= kMaxWidth,
          "segmentation_width must be in [0, 16384] (0 = native size)");
  require(max_corners >= 0 && max_corners <= 100000, "max_corners must be in [0, 100000]");
  require(edge_cell >= 2 && edge_cell <= 1024, "edge_cell must be in [2, 1024]");
  require(oddWindow(lk_window), "lk_window must be odd and in [3, 101]");
  require(lk_levels >= 0 && lk_levels <= 8, "lk_levels must be in [0, 8]");
  require(oddWindow(zncc_window), "zncc_window must be odd and in [3, 101]");
  require(ransac_iterations >= 1 && ransac_iterations <= 10000,
          "ransac_iterations must be in [1, 10000]");
  require(ransac_threshold > 0 && ransac_threshold <= 1000,
          "ransac_threshold must be in (0, 1000]");
  require(ransac_grid >= 1 && ransac_grid <= 16, "ransac_grid must be in [1, 16]");
  require(max_outer_iterations >= 1 && max_outer_iterations <= 100,
          "max_outer_iterations must be in [1, 100]");
  require(lambda >= 0 && lambda <= kMaxDifference,
          "lambda must be in [0, 65025] (d never exceeds 255^2)");
  require(lambda_residual_factor >= 0 && lambda_residual_factor <= 1000,
          "lambda_residual_factor must be in [0, 1000]");
  require(difference_blur >= 0 && difference_blur <= 20, "difference_blur must be in [0, 20]");
  require(gmm_clusters >= 1 && gmm_clusters <= 256, "gmm_clusters (K) must be in [1, 256]");
  require(cut_weight >= 0 && cut_weight <= 1000, "cut_weight must be in [0, 1000]");
  require(cut_band >= 0 && cut_band <= kMaxWidth,
          "cut_band must be in [0, 16384] (0 = whole image)");
  require(geodesic_gamma >= 0 && geodesic_gamma <= 100000, "geodesic_gamma must be in [0, 100000]");
}

}  // namespace movseg
