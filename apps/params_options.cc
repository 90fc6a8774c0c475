#include "params_options.h"

#include <map>

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
  command->add_option("--seed", params->seed, "Seed of the random choices")->capture_default_str();
}

}  // namespace movseg::cli
