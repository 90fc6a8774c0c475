// README's synthetic table, made as scripts/synth_table.sh makes it (one 60-frame `movseg synth`
// sequence per camera motion, seed 7, at 320x240 and 640x480, each size run by `movseg bench`):
// J of `dense` and `paper` per camera, and their error rates. A change that moves them must
// update README (the table once kept `paper`'s exact-cut figures for days after its default cut
// became coarse to fine).
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace movseg {
namespace {

struct Published {
  const char* camera;
  double dense, paper;  // J
};

struct PublishedSize {
  const char* size;
  Published cameras[5];
  double dense_error, paper_error;  // percent
};

// README, "Synthetic video with exact ground truth".
constexpr PublishedSize kReadme[] = {
    {"320x240",
     {{"pan", 0.994, 0.965},
      {"zoom", 0.970, 0.965},
      {"rotate", 0.990, 0.959},
      {"shake", 0.992, 0.954},
      {"static", 0.990, 0.966}},
     0.18,
     0.50},
    {"640x480",
     {{"pan", 0.989, 0.958},
      {"zoom", 0.971, 0.955},
      {"rotate", 0.969, 0.951},
      {"shake", 0.973, 0.955},
      {"static", 0.950, 0.954}},
     0.24,
     0.25}};

// About 30 s in Release; not under sanitizers, many times slower there (the accuracy tests of
// dense_test.cc and paper_accuracy_test.cc run the same code on shorter clips).
TEST(SynthTable, BenchGivesReadmesFigures) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the table's runs are left to the unsanitized build";
#endif
  const test::TempDir dir;
  for (const PublishedSize& size : kReadme) {
    SCOPED_TRACE(size.size);
    const std::string folder = dir / size.size;
    for (const Published& published : size.cameras) {
      ASSERT_EQ(test::runCli("synth -o " + folder + "/" + published.camera + " --size " +
                             size.size + " --camera " + published.camera +
                             " --frames 60 --seed 7")
                    .exit_code,
                0);
    }
    const std::string json = dir / (std::string(size.size) + ".json");
    const test::CommandResult run =
        test::runCli("bench " + folder + " --methods dense,paper --json " + json);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(json));
    // The table's methods: bench adds its MOG2 reference to every run.
    const auto inTable = [](const nlohmann::json& row) {
      return row.at("method") == "dense" || row.at("method") == "paper";
    };
    int found = 0;
    for (const nlohmann::json& row : report.at("rows")) {
      if (!inTable(row)) continue;
      for (const Published& published : size.cameras) {
        if (row.at("sequence") != published.camera) continue;
        const bool dense = row.at("method") == "dense";
        EXPECT_NEAR(row.at("J").get<double>(), dense ? published.dense : published.paper, 0.0005)
            << row.at("method") << ", " << published.camera;
        ++found;
      }
    }
    EXPECT_EQ(found, 10);
    int means = 0;
    for (const nlohmann::json& mean : report.at("means")) {
      if (!inTable(mean)) continue;
      ++means;
      const bool dense = mean.at("method") == "dense";
      EXPECT_NEAR(mean.at("error_rate").get<double>(), dense ? size.dense_error : size.paper_error,
                  0.005)
          << mean.at("method");
    }
    EXPECT_EQ(means, 2);
  }
}

}  // namespace
}  // namespace movseg
