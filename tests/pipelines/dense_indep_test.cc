// README's table of the sequences from a generator that shares nothing with ours
// (scripts/indep_synth.py, seeds 0-47, DAVIS textures among them), through the commands it names:
// `dense`'s mean J per camera motion and over the 48. A change that moves them must update
// README.
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace movseg {
namespace {

// README, "Synthetic video with exact ground truth": the independent generator's table.
const std::map<std::string, double> kReadme = {{"static", 0.845}, {"pan", 0.874},
                                               {"zoom", 0.838},   {"rotate", 0.864},
                                               {"shake", 0.752},  {"mix", 0.868}};
constexpr double kReadmeAll = 0.840;

// About two minutes: the generator's 48 clips (Python), then the bench on one thread. Run by
// `make long-run` (MOVSEG_LONG_TESTS=1), not by `make test`, whose budget the DAVIS tests fill.
TEST(DenseIndependent, BenchGivesReadmesFigures) {
  if (std::getenv("MOVSEG_LONG_TESTS") == nullptr) {
    GTEST_SKIP() << "a long test: MOVSEG_LONG_TESTS=1 (make long-run) runs it";
  }
  const std::string davis = test::davisDataset();
  if (davis.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA): the generator's textures";
  if (test::runShell("/usr/bin/python3 -c 'import cv2, numpy'") != 0) {
    GTEST_SKIP() << "no Python 3 with cv2 and numpy at /usr/bin/python3";
  }
  const test::TempDir dir;
  const std::string script = std::string(MOVSEG_SOURCE_DIR) + "/scripts/indep_synth.py";
  ASSERT_EQ(test::runShell("/usr/bin/python3 " + script + " " + dir / "data" +
                           " --seeds 0-47 --davis " + davis),
            0);
  const test::CommandResult run =
      test::runCli("bench " + dir / "data" + " --methods dense --json " + dir / "bench.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "bench.json"));
  std::map<std::string, std::pair<double, int>> sums;  // camera -> (sum of J, sequences)
  const std::regex name(R"(indep-(?:fractal|davis)-(\w+)-\d+)");
  for (const nlohmann::json& row : report.at("rows")) {
    if (row.at("method") != "dense") continue;  // MOG2 is timed beside it
    std::smatch match;
    const std::string sequence = row.at("sequence").get<std::string>();
    ASSERT_TRUE(std::regex_match(sequence, match, name)) << sequence;
    auto& [sum, count] = sums[match[1]];
    sum += row.at("J").get<double>();
    ++count;
  }
  double all = 0;
  for (const auto& [camera, readme] : kReadme) {
    const auto& [sum, count] = sums[camera];
    EXPECT_EQ(count, 8) << camera;
    EXPECT_NEAR(sum / count, readme, 0.0005) << camera;
    all += sum;
  }
  EXPECT_EQ(sums.size(), kReadme.size());
  EXPECT_NEAR(all / 48, kReadmeAll, 0.0005);
}

}  // namespace
}  // namespace movseg
