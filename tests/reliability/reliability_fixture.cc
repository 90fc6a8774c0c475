#include "reliability/reliability_fixture.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "movseg/fields.h"
#include "synth/synth.h"

namespace movseg::test {

void expectValidResult(const Result& result, cv::Size size) {
  ASSERT_EQ(result.mask.type(), CV_8UC1);
  ASSERT_EQ(result.mask.size(), size);
  EXPECT_EQ(cv::countNonZero((result.mask != 0) & (result.mask != 255)), 0);
  const Diagnostics& d = result.diagnostics;
  for (double v : d.model.val) EXPECT_TRUE(std::isfinite(v)) << "model " << d.model;
  for (const FieldInfo& field : diagnosticFields()) {
    const FieldValue value = diagnosticValue(d, field.name);
    if (const auto* real = std::get_if<double>(&value)) {
      EXPECT_TRUE(std::isfinite(*real) && *real >= 0) << field.name << " = " << *real;
    }
    if (const auto* count = std::get_if<int>(&value)) {
      EXPECT_GE(*count, 0) << field.name;
    }
  }
  for (const Feature& f : result.features) {
    EXPECT_TRUE(std::isfinite(f.position.x) && std::isfinite(f.position.y));
  }
}

double foregroundShare(const cv::Mat& mask) {
  return static_cast<double>(cv::countNonZero(mask)) / static_cast<double>(mask.total());
}

cv::Mat view(const cv::Mat& world, cv::Point at, cv::Size size) {
  return world(cv::Rect(at, size)).clone();
}

std::vector<cv::Mat> masksOf(const std::vector<cv::Mat>& frames, const Params& params) {
  Segmenter segmenter(params);
  std::vector<cv::Mat> masks;
  for (const cv::Mat& frame : frames) masks.push_back(segmenter.process(frame).mask);
  return masks;
}

std::vector<cv::Mat> synthFrames(int count, std::uint64_t seed, cv::Size size) {
  SynthOptions options;
  options.frames = count;
  options.seed = seed;
  options.size = size;
  const SynthSequence sequence(options);
  std::vector<cv::Mat> frames;
  for (int t = 0; t < count; ++t) frames.push_back(sequence.frame(t).frame);
  return frames;
}

bool identical(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b) {
  const auto same = [](const cv::Mat& x, const cv::Mat& y) {
    return x.size() == y.size() && x.type() == y.type() && cv::norm(x, y, cv::NORM_INF) == 0;
  };
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same);
}

std::vector<std::string> filesIn(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace movseg::test
