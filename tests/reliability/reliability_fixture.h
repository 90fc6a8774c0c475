// Checks and scenes shared by the reliability tests (docs/reliability.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "movseg/segmenter.h"

namespace movseg::test {

// process()'s promises for any frame it accepts: a CV_8U mask of the frame's size holding only
// 0 and 255, and diagnostics without NaN or infinity.
void expectValidResult(const Result& result, cv::Size size);

// The share of a mask's pixels that are foreground, in [0, 1].
double foregroundShare(const cv::Mat& mask);

// What a camera sees of `world` through a `size` window at `at`: moving `at` pans the camera.
cv::Mat view(const cv::Mat& world, cv::Point at, cv::Size size);

// The masks of one Segmenter fed `frames` in order.
std::vector<cv::Mat> masksOf(const std::vector<cv::Mat>& frames, const Params& params = Params());

// The frames of a deterministic synthetic sequence (movseg::SynthSequence, default options).
std::vector<cv::Mat> synthFrames(int count, std::uint64_t seed, cv::Size size = {320, 240});

// Whether two lists of masks are equal pixel for pixel.
bool identical(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b);

// The files of a folder, sorted by name.
std::vector<std::string> filesIn(const std::string& folder);

}  // namespace movseg::test
