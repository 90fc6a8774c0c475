#include "params_options.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace movseg::cli {

void addParamsOptions(CLI::App* command, Params* params) {
  const std::map<std::string, MotionModel> models{{"affine", MotionModel::kAffine},
                                                  {"homography", MotionModel::kHomography}};
  command->add_flag("--static", params->static_camera, "Static camera: skip alignment");
  command->add_option("--model", params->motion_model, "Camera model")
      ->transform(CLI::CheckedTransformer(models, CLI::ignore_case))
      ->capture_default_str();
  command->add_option("--lambda", params->lambda, "Threshold of eq. (3) on d (8-bit units^2)")
      ->capture_default_str();
  command->add_option("--gmm-k", params->gmm_clusters, "Clusters per colour GMM (K)")
      ->capture_default_str();
  command->add_option("--cut-weight", params->cut_weight, "Pairwise weight of eq. (6)")
      ->capture_default_str();
  command->add_option("--alignment-width", params->alignment_width,
                      "Width for alignment (0 = native)")
      ->capture_default_str();
  command->add_option("--segmentation-width", params->segmentation_width,
                      "Width for the geodesic cut (0 = native)")
      ->capture_default_str();
  command->add_option("--seed", params->seed, "Seed of the random choices")
      ->check(kNotNegative)
      ->capture_default_str();
  command->add_option_function<std::vector<std::string>>(
      "--set", [params](const std::vector<std::string>& items) {
        for (const std::string& item : items) setParam(params, item);
      },
      "Set any Params field: --set name=value (repeatable; see include/movseg/params.h)");
}

void setParam(Params* params, const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos) throw CLI::ValidationError("--set", "expected name=value, got '" + assignment + "'");
  const std::string name = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  auto number = [&]() {
    try {
      size_t used = 0;
      const double v = std::stod(value, &used);
      if (used == value.size()) return v;
    } catch (const std::exception&) {
    }
    throw CLI::ValidationError("--set", "'" + value + "' is not a number for " + name);
  };
  auto integer = [&]() {
    const double v = number();
    if (v != std::floor(v) || v < std::numeric_limits<int>::min() ||
        v > std::numeric_limits<int>::max()) {
      throw CLI::ValidationError("--set", "'" + value + "' is not an integer for " + name);
    }
    return static_cast<int>(v);
  };
  auto boolean = [&]() { return value == "1" || value == "true" || value == "on"; };
  const std::map<std::string, std::function<void()>> setters{
      {"static_camera", [&] { params->static_camera = boolean(); }},
      {"alignment_width", [&] { params->alignment_width = integer(); }},
      {"max_corners", [&] { params->max_corners = integer(); }},
      {"edge_cell", [&] { params->edge_cell = integer(); }},
      {"max_tracked_features", [&] { params->max_tracked_features = integer(); }},
      {"lk_window", [&] { params->lk_window = integer(); }},
      {"lk_levels", [&] { params->lk_levels = integer(); }},
      {"zncc_window", [&] { params->zncc_window = integer(); }},
      {"ransac_iterations", [&] { params->ransac_iterations = integer(); }},
      {"ransac_threshold", [&] { params->ransac_threshold = number(); }},
      {"ransac_grid", [&] { params->ransac_grid = integer(); }},
      {"max_outer_iterations", [&] { params->max_outer_iterations = integer(); }},
      {"warm_start", [&] { params->warm_start = boolean(); }},
      {"lambda", [&] { params->lambda = number(); }},
      {"lambda_residual_factor", [&] { params->lambda_residual_factor = number(); }},
      {"difference_blur", [&] { params->difference_blur = number(); }},
      {"gmm_clusters", [&] { params->gmm_clusters = integer(); }},
      {"gmm_refine", [&] { params->gmm_refine = boolean(); }},
      {"cut_weight", [&] { params->cut_weight = number(); }},
      {"geodesic_gamma", [&] { params->geodesic_gamma = number(); }},
      {"cut_band", [&] { params->cut_band = integer(); }},
      {"segmentation_width", [&] { params->segmentation_width = integer(); }},
  };
  const auto setter = setters.find(name);
  if (setter == setters.end()) throw CLI::ValidationError("--set", "unknown parameter '" + name + "'");
  setter->second();
}

}  // namespace movseg::cli
