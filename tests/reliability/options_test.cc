// Out-of-range parameters and options are refused with one clear line, never run (an absurd
// value could otherwise make a frame that never ends).
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "movseg/fields.h"
#include "test_support.h"

namespace movseg {
namespace {

// Each bad option: exit code 2 and a single line "movseg: error: ..." naming what is wrong.
TEST(Options, BadCliOptionsExitWithOneLine) {
  test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames 2 --size 64x48").exit_code, 0);
  const std::string segment = "segment " + (dir / "clip/frames") + " -o " + (dir / "out") + " -q ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {segment + "--frobnicate", "frobnicate"},
      {segment + "--gmm-k 0", "gmm_clusters"},
      {segment + "--lambda -1", "lambda"},
      {segment + "--lambda inf", "lambda"},
      {segment + "--cut-weight -0.5", "cut_weight"},
      {segment + "--alignment-width -5", "alignment_width"},
      {segment + "--segmentation-width 1000000", "segmentation_width"},
      {segment + "--max-frames -1", "--max-frames"},
      {segment + "--timeout inf", "--timeout"},
      {segment + "--timeout nan", "--timeout"},  // NaN passes every range check
      {segment + "--set ransac_iterations=1e8", "ransac_iterations"},
      {segment + "--set max_corners=2000000000", "max_corners"},
      {segment + "--set lk_window=4", "lk_window"},
      {segment + "--set lambda=abc", "lambda"},
      {segment + "--set static_camera=yes", "static_camera"},
      {segment + "--set gmm_refine=maybe", "gmm_refine"},
      {segment + "--static=maybe", "static_camera"},
      {segment + "--method fast", "method"},
      {segment + "--set seed=-1", "seed"},
      {segment + "--set nothing=1", "nothing"},
      {segment + "--set lambda", "name=value"},
      // Two values, by its option and by --set or by --set twice: neither wins silently (the
      // same value twice is fine: Options.EveryParameterIsSetByNameOrByItsOption).
      {segment + "--method dense --set method=paper", "method"},
      {segment + "--static --set static_camera=false", "static_camera"},
      {segment + "--set lambda=3 --set lambda=4", "lambda"},
      {"bench " + (dir / "clip") + " --lk-window 5 --set lk_window=7", "lk_window"},
      {"synth -o " + (dir / "s") + " --size -5x10", "--size"},
      {"synth -o " + (dir / "s") + " --size 0x0", "size"},
      {"synth -o " + (dir / "s") + " --frames 0", "frames"},
      {"synth -o " + (dir / "s") + " --objects 9", "objects"},
      {"bench " + (dir / "clip") + " --methods fast", "--methods"},
      {"demo -o " + (dir / "d") + " --frames 0", "frames"},
      {"demo -o " + (dir / "d") + " --frames 1", "frames"},  // nothing to score: no J nan
      {"demo -o " + (dir / "d") + " --lambda -1", "lambda"},
  };
  for (const auto& [arguments, named] : cases) {
    SCOPED_TRACE(arguments);
    test::expectOneLineError(test::runCli(arguments), named, test::kExitUsage);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "d")) << "demo wrote before checking its options";
}

// Every field of params.def can be set from the command line, by --set and by its own option,
// to a value other than its default, and the run uses it (its manifest records the settings, as
// does bench's JSON).
TEST(Options, EveryParameterIsSetByNameOrByItsOption) {
  test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames 3 --size 64x48").exit_code, 0);
  std::string by_set, by_option;
  std::string bench_by_set, bench_by_option;  // bench all but the method: its --methods give it
  const Params defaults;
  Params expected;
  for (const FieldInfo& field : paramFields()) {
    const std::string value = test::otherParamValue(field, defaults);
    setParam(&expected, field.name, value);
    ASSERT_NE(toText(paramValue(expected, field.name)), toText(paramValue(defaults, field.name)))
        << field.name;
    const std::string set = " --set " + field.name + "=" + value;
    std::string option = field.name;
    for (char& c : option) c = c == '_' ? '-' : c;
    option = " --" + option + (field.type == FieldType::kBool ? "=" : " ") + value;
    by_set += set;
    by_option += option;
    if (field.name == "method") continue;
    bench_by_set += set;
    bench_by_option += option;
  }
  expected.check();
  const std::string segment =
      "segment " + (dir / "clip/frames") + " -o " + (dir / "out") + " -q --overwrite";
  // The settings a run's manifest records, against `expected`.
  // bench's JSON records them too, but for `method`: each row names its own.
  const auto expectSettings = [&](const std::string& manifest) {
    const nlohmann::json settings = nlohmann::json::parse(std::ifstream(manifest)).at("settings");
    for (const FieldInfo& field : paramFields()) {
      if (field.name == "method" && !settings.contains("method")) continue;
      EXPECT_EQ(settings.at(field.name), toText(paramValue(expected, field.name))) << field.name;
    }
    EXPECT_GE(settings.size(), paramFields().size() - 1);
  };
  for (const std::string& options : {by_set, by_option}) {
    SCOPED_TRACE(options);
    const test::CommandResult run = test::runCli(segment + options);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    expectSettings(dir / "out/movseg-run.json");
  }
  // demo and bench take the same options.
  const test::CommandResult demo =
      test::runCli("demo -o " + (dir / "demo") + " --frames 3" + by_option);
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  expectSettings(dir / "demo/segmented/movseg-run.json");
  for (const std::string& options : {bench_by_set, bench_by_option}) {
    const test::CommandResult bench = test::runCli("bench " + (dir / "clip") +
                                                   " --methods dense --json " +
                                                   (dir / "bench.json") + options);
    EXPECT_EQ(bench.exit_code, 0) << bench.output;
    expectSettings(dir / "bench.json");
  }
  const test::CommandResult run = test::runCli(segment + " --set static_camera=TRUE --static");
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

// The short forms README names: --model for motion_model, --static for static_camera, --gmm-k
// for gmm_clusters.
TEST(Options, ShortFormsSetTheirParameters) {
  test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames 3 --size 160x120").exit_code, 0);
  const test::CommandResult run =
      test::runCli("segment " + (dir / "clip/frames") + " -o " + (dir / "out") +
                   " -q --model homography --static --gmm-k 7");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json settings =
      nlohmann::json::parse(std::ifstream(dir / "out/movseg-run.json")).at("settings");
  EXPECT_EQ(settings.at("motion_model"), "homography");
  EXPECT_EQ(settings.at("static_camera"), "true");
  EXPECT_EQ(settings.at("gmm_clusters"), "7");
}

// Booleans of --set are true, false, 1 or 0 in any case, and they take effect: a static camera
// tracks nothing.
TEST(Options, SetBooleansInAnyCaseTakeEffect) {
  test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + (dir / "clip") + " --frames 2 --size 96x72").exit_code, 0);
  const auto tracksOfSecondFrame = [&](const std::string& value) {
    const std::string stats = dir / "stats.jsonl";
    const test::CommandResult run =
        test::runCli("segment " + (dir / "clip/frames") + " -o " + (dir / "out") +
                     " -q --overwrite --method paper --stats " + stats + " --set static_camera=" + value);
    EXPECT_EQ(run.exit_code, 0) << value << "\n" << run.output;
    std::ifstream in(stats);
    std::string line;
    std::getline(in, line);
    std::getline(in, line);
    return nlohmann::json::parse(line).at("tracks").get<int>();
  };
  for (const std::string value : {"TRUE", "True", "true", "1"}) EXPECT_EQ(tracksOfSecondFrame(value), 0) << value;
  for (const std::string value : {"FALSE", "False", "false", "0"}) EXPECT_GT(tracksOfSecondFrame(value), 0) << value;
}

}  // namespace
}  // namespace movseg
