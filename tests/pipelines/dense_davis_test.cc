// README's DAVIS table for `dense`, through the command it names (`movseg bench`): three of the
// shorter sequences, J and F per sequence as printed there. A change that moves them must
// update README.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace movseg {
namespace {

struct Published {
  const char* sequence;
  double j, f;
};

// README, "J per sequence" (J) and the bench run behind it (F).
constexpr Published kReadme[] = {{"car-shadow", 0.647, 0.617},
                                 {"motocross-jump", 0.574, 0.482},
                                 {"scooter-black", 0.691, 0.508}};

TEST(DenseDavis, BenchGivesReadmesFigures) {
  const test::TempDir dir;
  for (const Published& row : kReadme) {
    const std::string folder = test::davisSequence(row.sequence);
    if (folder.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
    std::filesystem::create_directory_symlink(folder, dir / row.sequence);
  }
  const test::CommandResult run =
      test::runCli("bench " + dir.path() + " --methods dense --json " + dir / "bench.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "bench.json"));
  int found = 0;
  for (const nlohmann::json& row : report.at("rows")) {
    if (row.at("method") != "dense") continue;  // MOG2 is timed beside it
    for (const Published& published : kReadme) {
      if (row.at("sequence") != published.sequence) continue;
      ++found;
      EXPECT_NEAR(row.at("J").get<double>(), published.j, 0.0005) << published.sequence;
      EXPECT_NEAR(row.at("F").get<double>(), published.f, 0.0005) << published.sequence;
    }
  }
  EXPECT_EQ(found, 3);
}

}  // namespace
}  // namespace movseg
