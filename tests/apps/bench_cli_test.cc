// `movseg bench` end to end, and the ranking it must keep: on a synthetic moving-camera clip the
// paper's method beats plain MOG2 (which cannot follow a moving camera) by a clear margin.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace movseg {
namespace {

TEST(BenchCli, PaperBeatsMog2ByAClearMarginOnSyntheticVideo) {
  const test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + dir / "data/pan" + " --frames 30 --camera pan --seed 3")
                .exit_code, 0);
  const test::CommandResult bench =
      test::runCli("bench " + dir / "data" + " --methods paper,mog2 --json " + dir / "bench.json");
  ASSERT_EQ(bench.exit_code, 0) << bench.output;
  EXPECT_NE(bench.output.find("MEAN"), std::string::npos);

  std::ifstream in(dir / "bench.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  double paper = -1, mog2 = -1;
  for (const auto& row : report.at("means")) {
    (row.at("method") == "paper" ? paper : mog2) = row.at("J").get<double>();
    EXPECT_GT(row.at("ms_per_frame").get<double>(), 0.0);
  }
  EXPECT_GE(paper, mog2 + 0.2) << "paper J " << paper << ", mog2 J " << mog2;
  EXPECT_GT(paper, 0.7);
}

TEST(BenchCli, RejectsUnknownMethodAndBadSize) {
  const test::TempDir dir;
  ASSERT_EQ(test::runCli("synth -o " + dir / "data/s" + " --frames 3").exit_code, 0);
  const test::CommandResult unknown = test::runCli("bench " + dir / "data" + " --methods nope");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("movseg: error:"), std::string::npos);
  const test::CommandResult size = test::runCli("bench " + dir / "data" + " --size 0x5");
  EXPECT_NE(size.exit_code, 0);
  EXPECT_NE(size.output.find("--size"), std::string::npos);
}

TEST(DemoCli, SegmentsTheSyntheticClipAndPrintsItsAccuracy) {
  const test::TempDir dir;
  const test::CommandResult demo = test::runCli("demo -o " + dir / "demo" + " --frames 20");
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  EXPECT_NE(demo.output.find("demo: J "), std::string::npos) << demo.output;
  std::ifstream mask(dir / "demo/segmented/00019.png");
  EXPECT_TRUE(mask.good());
}

}  // namespace
}  // namespace movseg
