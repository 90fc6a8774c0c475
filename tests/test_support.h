// Helpers shared by the tests.
#pragma once

#include <string>

namespace movseg::test {

// A fresh empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs build/movseg with `arguments` (a shell-quoted string) and captures its output.
CommandResult runCli(const std::string& arguments);

// The folder of a DAVIS 2016 sequence (frames/, masks/) under $MOVSEG_DATA/davis2016, or the
// shared data next to the source tree; "" when it is not there (tests then skip).
std::string davisSequence(const std::string& name);

}  // namespace movseg::test

#include <cstdint>

#include <opencv2/core.hpp>

namespace movseg::test {

// A richly textured BGR image (smoothed noise at several scales), the same for the same seed.
cv::Mat texture(cv::Size size, std::uint64_t seed);

// Maximum distance between the images of the four corners of a w x h frame under two models.
double cornerError(const cv::Matx33d& estimated, const cv::Matx33d& truth, cv::Size size);

}  // namespace movseg::test
