// Out-of-range parameters and options are refused with one clear line, never run (an absurd
// value could otherwise make a frame that never ends).
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "movseg/params.h"
#include "test_support.h"

namespace movseg {
namespace {

TEST(Options, OutOfRangeParamsAreRejectedByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, std::function<void(Params&)>>> cases{
      {"alignment_width", [](Params& p) { p.alignment_width = -1; }},
      {"alignment_width", [](Params& p) { p.alignment_width = 100000; }},
      {"segmentation_width", [](Params& p) { p.segmentation_width = -320; }},
      {"max_corners", [](Params& p) { p.max_corners = 2000000000; }},
      {"edge_cell", [](Params& p) { p.edge_cell = 1; }},
      {"lk_window", [](Params& p) { p.lk_window = 1001; }},
      {"zncc_window", [](Params& p) { p.zncc_window = 9999; }},
      {"ransac_iterations", [](Params& p) { p.ransac_iterations = 1000000000; }},
      {"ransac_threshold", [&](Params& p) { p.ransac_threshold = nan; }},
      {"max_outer_iterations", [](Params& p) { p.max_outer_iterations = 100000000; }},
      {"lambda", [](Params& p) { p.lambda = -1; }},
      {"lambda", [&](Params& p) { p.lambda = inf; }},
      {"lambda_residual_factor", [&](Params& p) { p.lambda_residual_factor = nan; }},
      {"difference_blur", [](Params& p) { p.difference_blur = 21; }},
      {"gmm_clusters", [](Params& p) { p.gmm_clusters = 0; }},
      {"gmm_clusters", [](Params& p) { p.gmm_clusters = 1000000000; }},
      {"cut_weight", [&](Params& p) { p.cut_weight = inf; }},
      {"cut_band", [](Params& p) { p.cut_band = -1; }},
      {"geodesic_gamma", [](Params& p) { p.geodesic_gamma = 1e308; }},
  };
  for (const auto& [name, set] : cases) {
    Params params;
    set(params);
    try {
      params.check();
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

// Each bad option: a non-zero exit and a single line "movseg: error: ..." naming what is wrong.
TEST(Options, BadCliOptionsExitWithOneLine) {
  test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames 2 --size 64x48").exit_code, 0);
  const std::string segment = "segment " + (dir / "clip/frames") + " -o " + (dir / "out") + " -q ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {segment + "--gmm-k 0", "gmm_clusters"},
      {segment + "--lambda -1", "lambda"},
      {segment + "--lambda inf", "lambda"},
      {segment + "--cut-weight -0.5", "cut_weight"},
      {segment + "--alignment-width -5", "alignment_width"},
      {segment + "--segmentation-width 1000000", "segmentation_width"},
      {segment + "--max-frames -1", "--max-frames"},
      {segment + "--set ransac_iterations=1e8", "ransac_iterations"},
      {segment + "--set max_corners=2000000000", "max_corners"},
      {segment + "--set lk_window=4", "lk_window"},
      {segment + "--set lambda=abc", "lambda"},
      {"synth -o " + (dir / "s") + " --size -5x10", "--size"},
      {"synth -o " + (dir / "s") + " --size 0x0", "size"},
      {"synth -o " + (dir / "s") + " --frames 0", "frames"},
      {"synth -o " + (dir / "s") + " --objects 9", "objects"},
  };
  for (const auto& [arguments, named] : cases) {
    const test::CommandResult run = test::runCli(arguments);
    EXPECT_NE(run.exit_code, 0) << arguments;
    EXPECT_EQ(run.output.rfind("movseg: error: ", 0), 0u) << arguments << "\n" << run.output;
    EXPECT_EQ(run.output.find('\n'), run.output.size() - 1) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(named), std::string::npos) << arguments << "\n" << run.output;
  }
}

}  // namespace
}  // namespace movseg
