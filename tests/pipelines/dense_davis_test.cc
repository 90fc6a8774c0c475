// README's DAVIS tables, through the command they name (`movseg bench --methods dense,paper`):
// J and F of `dense` on every one of the 15 sequences and their means, `paper`'s J on every one
// (the reproduction's figures), and the means of `dense`, `paper` and MOG2 with their error
// rates, as printed there. A change that moves them must update README.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/metrics.h"
#include "movseg/segmenter.h"
#include "test_support.h"

namespace movseg {
namespace {

struct Published {
  const char* sequence;
  double j, f;    // dense
  double paper_j;
};

// README, "J per sequence" (J) and the bench run behind it (F).
constexpr Published kReadme[] = {
    {"blackswan", 0.395, 0.678, 0.476},      {"bmx-trees", 0.465, 0.596, 0.369},
    {"breakdance", 0.733, 0.692, 0.503},     {"car-roundabout", 0.856, 0.706, 0.360},
    {"car-shadow", 0.683, 0.638, 0.329},     {"cows", 0.756, 0.613, 0.295},
    {"dance-twirl", 0.772, 0.722, 0.529},    {"dog", 0.882, 0.850, 0.387},
    {"drift-straight", 0.601, 0.493, 0.274}, {"goat", 0.150, 0.316, 0.110},
    {"horsejump-high", 0.769, 0.810, 0.374}, {"kite-surf", 0.189, 0.322, 0.205},
    {"motocross-jump", 0.538, 0.475, 0.428}, {"paragliding-launch", 0.607, 0.232, 0.547},
    {"scooter-black", 0.708, 0.537, 0.341}};

struct PublishedMean {
  const char* method;
  double j, f, error_percent;
};
// README, the DAVIS table's first three rows.
constexpr PublishedMean kReadmeMeans[] = {
    {"dense", 0.607, 0.579, 5.61}, {"paper", 0.368, 0.338, 10.81}, {"mog2", 0.129, 0.154, 35.71}};

// One thread: about a minute and a half (`--threads 2` would add its throughput runs, three times
// as long).
// Not under sanitizers, many times slower there: the test below runs the same code on one
// sequence under them.
TEST(DenseDavis, BenchGivesReadmesFigures) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the whole DAVIS run is left to the unsanitized build";
#endif
  const std::string data = test::davisDataset();
  if (data.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  const test::TempDir dir;
  const test::CommandResult run =
      test::runCli("bench " + data + " --methods dense,paper --json " + dir / "bench.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "bench.json"));
  int found = 0;
  for (const nlohmann::json& row : report.at("rows")) {
    for (const Published& published : kReadme) {
      if (row.at("sequence") != published.sequence) continue;
      const double j = row.at("J").get<double>();
      if (row.at("method") == "dense") {
        ++found;
        EXPECT_NEAR(j, published.j, 0.0005) << published.sequence;
        EXPECT_NEAR(row.at("F").get<double>(), published.f, 0.0005) << published.sequence;
      } else if (row.at("method") == "paper") {
        ++found;
        EXPECT_NEAR(j, published.paper_j, 0.0005) << "paper, " << published.sequence;
      }
    }
  }
  EXPECT_EQ(found, 30);
  int means = 0;
  for (const nlohmann::json& mean : report.at("means")) {
    for (const PublishedMean& published : kReadmeMeans) {
      if (mean.at("method") != published.method) continue;
      ++means;
      SCOPED_TRACE(published.method);
      EXPECT_NEAR(mean.at("J").get<double>(), published.j, 0.0005);
      EXPECT_NEAR(mean.at("F").get<double>(), published.f, 0.0005);
      EXPECT_NEAR(mean.at("error_rate").get<double>(), published.error_percent, 0.005);
    }
  }
  EXPECT_EQ(means, 3);
}

// The ground truth of a DAVIS frame file: <sequence>/masks/<its name>.png.
std::filesystem::path maskOf(const std::string& frame) {
  const std::filesystem::path path(frame);
  return path.parent_path().parent_path() / "masks" /
         std::filesystem::path(path.filename()).replace_extension(".png");
}

// A DAVIS sequence filmed worse, as scripts/degrade.py writes its variants for README's tables:
// frame t, as read, becomes film(frame, t) (one picture, or two for a repeated frame), numbered
// on from 0 and written as JPEG at quality 95 into FOLDER/frames, each beside a link to its mask
// in FOLDER/masks.
using Filming = std::function<std::vector<cv::Mat>(const cv::Mat& frame, int t)>;
void writeFilmed(const std::string& sequence, const std::string& folder, const Filming& film) {
  namespace fs = std::filesystem;
  fs::create_directories(folder + "/frames");
  fs::create_directories(folder + "/masks");
  const std::vector<std::string> frames = test::davisFrames(sequence, 1000);
  int out = 0;
  for (size_t t = 0; t < frames.size(); ++t) {
    const fs::path mask = maskOf(frames[t]);
    for (const cv::Mat& picture : film(cv::imread(frames[t]), static_cast<int>(t))) {
      char name[16];
      std::snprintf(name, sizeof name, "%05d", out++);
      cv::imwrite(folder + "/frames/" + name + ".jpg", picture, {cv::IMWRITE_JPEG_QUALITY, 95});
      fs::create_symlink(mask, folder + "/masks/" + name + ".png");
    }
  }
}

// degrade.py's change of light: each level times `gain` in single precision, rounded half up
// and clipped to 255, as NumPy computes it there.
cv::Mat lit(const cv::Mat& frame, float gain) {
  cv::Mat table(1, 256, CV_8U);
  for (int v = 0; v < 256; ++v) {
    table.at<uchar>(v) = static_cast<uchar>(std::min(255.f, static_cast<float>(v) * gain + 0.5f));
  }
  cv::Mat out;
  cv::LUT(frame, table, out);
  return out;
}

// README, "Changes of light" and "Repeated frames": at 320x240, a mains-lit cows (every other
// frame 8 % darker, the others 8 % brighter), dog with an exposure 30 % brighter from its 21st
// frame, and cows with every fifth frame shown twice, written as degrade.py writes them and
// benched as README's command does. Without the fitted change of light the flicker's cows gave
// 0.26 and the step's dog 0.79; without repeats taken as such, the repeated cows 0.62. In the
// same bench the 15 sequences as they are: README's speed table's 320x240 row, J 0.601 and F
// 0.583 (about a minute in all).
TEST(DenseDavis, At320x240GivesReadmesFigures) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "left to the unsanitized build: the bonnet test runs `dense` on DAVIS there";
#endif
  const test::TempDir dir;
  std::filesystem::create_directories(dir / "data");
  for (const Published& published : kReadme) {
    const std::string sequence = test::davisSequence(published.sequence);
    if (sequence.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
    std::filesystem::create_directory_symlink(sequence, dir / "data/" + published.sequence);
  }
  writeFilmed("cows", dir / "data/cows-flicker", [](const cv::Mat& frame, int t) {
    return std::vector<cv::Mat>{lit(frame, t % 2 ? 1.08f : 0.92f)};
  });
  writeFilmed("dog", dir / "data/dog-step", [](const cv::Mat& frame, int t) {
    return std::vector<cv::Mat>{lit(frame, t >= 20 ? 1.3f : 1.f)};
  });
  writeFilmed("cows", dir / "data/cows-repeat", [](const cv::Mat& frame, int t) {
    return std::vector<cv::Mat>(t % 5 == 4 ? 2 : 1, frame);
  });
  const test::CommandResult run = test::runCli(
      "bench " + dir / "data" + " --methods dense --size 320x240 --json " + dir / "bench.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::pair<std::string, double>> readme = {
      {"cows-flicker", 0.758}, {"dog-step", 0.883}, {"cows-repeat", 0.794}};
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "bench.json"));
  size_t found = 0;
  double plain_j = 0, plain_f = 0;  // sums over kReadme's sequences, as they are
  for (const nlohmann::json& row : report.at("rows")) {
    if (row.at("method") != "dense") continue;
    for (const auto& [sequence, j] : readme) {
      if (row.at("sequence") != sequence) continue;
      ++found;
      EXPECT_NEAR(row.at("J").get<double>(), j, 0.0005) << sequence;
    }
    for (const Published& published : kReadme) {
      if (row.at("sequence") != published.sequence) continue;
      ++found;
      plain_j += row.at("J").get<double>();
      plain_f += row.at("F").get<double>();
    }
  }
  const auto plain = static_cast<double>(std::size(kReadme));
  ASSERT_EQ(found, readme.size() + std::size(kReadme));
  EXPECT_NEAR(plain_j / plain, 0.601, 0.0005);
  EXPECT_NEAR(plain_f / plain, 0.583, 0.0005);
}

// Mean J of `dense` on a DAVIS sequence whose frames carry `overlay` where `region` is non-zero,
// the segmenter told to ignore `ignored` (none when empty); the region is not scored.
double meanJWithOverlay(const std::vector<std::string>& frames, const cv::Mat& overlay,
                        const cv::Mat& region, const cv::Mat& ignored) {
  Segmenter segmenter(test::withMethod(Method::kDense));
  segmenter.setIgnoredRegion(ignored);
  double sum = 0;
  for (size_t t = 0; t < frames.size(); ++t) {
    cv::Mat frame = cv::imread(frames[t]);
    overlay.copyTo(frame, region);
    const cv::Mat mask = segmenter.process(frame).mask;
    if (t == 0) continue;  // no previous frame, no motion cue
    sum += scoreFrame(mask, cv::imread(maskOf(frames[t]), cv::IMREAD_GRAYSCALE), region).j;
  }
  return sum / static_cast<double>(frames.size() - 1);
}

// README, "Things fixed to the camera": a dash-cam's bonnet (a textured ellipse over the bottom
// eighth) and a burnt-in timestamp pasted on car-roundabout, whose camera pans with a car. Told
// to ignore them, `dense` finds the car as on the sequence itself: measured 0.856 (README's
// 0.856 without them). Told nothing, 0.053: they stand still while the camera turns. With the
// camera sampled up to the region's edge, 0.500: the flow next to it goes its way, and a still
// region reads as depth at infinity.
TEST(DenseDavis, ABonnetAndATimestampAreIgnoredWhenSaidSo) {
  const std::vector<std::string> frames = test::davisFrames("car-roundabout", 1000);
  if (frames.empty()) GTEST_SKIP() << "no DAVIS data (set MOVSEG_DATA)";
  const cv::Size size = cv::imread(frames[0]).size();
  cv::Mat region = cv::Mat::zeros(size, CV_8U);
  cv::ellipse(region, {size.width / 2, size.height * 5 / 4},
              {size.width * 2 / 3, size.height * 3 / 8}, 0, 0, 360, 255, cv::FILLED);
  const cv::Rect timestamp(8, 8, 230, 30);
  region(timestamp).setTo(255);
  cv::Mat overlay = test::texture(size, 3) / 2;
  overlay(timestamp).setTo(cv::Scalar::all(0));
  cv::putText(overlay, "2026-11-26 12:00:00", {14, 30}, cv::FONT_HERSHEY_SIMPLEX, 0.6,
              cv::Scalar::all(255), 2);
  // Deterministic: the measured figures, to the third decimal README quotes.
  EXPECT_NEAR(meanJWithOverlay(frames, overlay, region, region), 0.856, 0.005);
  EXPECT_NEAR(meanJWithOverlay(frames, overlay, region, cv::Mat()), 0.053, 0.005);
}

}  // namespace
}  // namespace movseg
