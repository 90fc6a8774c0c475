#include "test_support.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

namespace movseg::test {

TempDir::TempDir() {
  std::random_device device;
  const auto base = std::filesystem::temp_directory_path();
  do {
    path_ = (base / ("movseg-test-" + std::to_string(device()))).string();
  } while (std::filesystem::exists(path_));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

CommandResult runCli(const std::string& arguments) {
  CommandResult result;
  const std::string command = std::string(MOVSEG_CLI_PATH) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string davisSequence(const std::string& name) {
  const char* data = std::getenv("MOVSEG_DATA");
  const std::string root = data != nullptr ? data : std::string(MOVSEG_SOURCE_DIR) + "/../shared/data";
  const std::string folder = root + "/davis2016/" + name;
  return std::filesystem::is_directory(folder + "/frames") ? folder : "";
}

}  // namespace movseg::test

#include <opencv2/imgproc.hpp>

namespace movseg::test {

cv::Mat texture(cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat sum(size, CV_32FC3, cv::Scalar::all(0));
  for (int scale : {1, 3, 9, 27}) {
    const cv::Size small((size.width + scale - 1) / scale, (size.height + scale - 1) / scale);
    cv::Mat noise(small, CV_32FC3);
    rng.fill(noise, cv::RNG::UNIFORM, cv::Scalar::all(-1), cv::Scalar::all(1));
    cv::Mat up;
    cv::resize(noise, up, size, 0, 0, cv::INTER_CUBIC);
    sum += up;
  }
  cv::Mat out;
  sum.convertTo(out, CV_8UC3, 40, 128);
  return out;
}

double cornerError(const cv::Matx33d& estimated, const cv::Matx33d& truth, cv::Size size) {
  double worst = 0;
  for (const cv::Vec3d& c : {cv::Vec3d(0, 0, 1), cv::Vec3d(size.width, 0, 1),
                             cv::Vec3d(0, size.height, 1), cv::Vec3d(size.width, size.height, 1)}) {
    const cv::Vec3d a = estimated * c, b = truth * c;
    worst = std::max(worst, std::hypot(a[0] / a[2] - b[0] / b[2], a[1] / a[2] - b[1] / b[2]));
  }
  return worst;
}

}  // namespace movseg::test
