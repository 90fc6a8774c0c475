// Helpers shared by the tests.
#pragma once

#include <sys/types.h>

#include <string>
#include <thread>
#include <vector>

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

// runCli() under a file-size limit (RLIMIT_FSIZE, as a full disk): a write past `bytes` fails.
CommandResult runCliWithFileLimit(long bytes, const std::string& arguments);

// The CLI's exit codes (README, "Bad input"; apps/commands.h).
constexpr int kExitRunFailed = 1;  // bad input, a failed write
constexpr int kExitUsage = 2;      // an unknown option, a value out of range, bad output paths

// Expects exit code `code` and exactly one line "movseg: error: ..." naming `needle`.
void expectOneLineError(const CommandResult& result, const std::string& needle, int code);

// `movseg ARGS...` started in the background, its stdout and stderr going to `log`; its pid.
pid_t startCli(const std::vector<std::string>& args, const std::string& log);

// A TCP server on 127.0.0.1 for stream tests. Without `video` it accepts connections and never
// answers; with it, it answers the first request with an HTTP header and those bytes, then
// stays silent until the client hangs up (a stalled stream).
class LocalServer {
 public:
  explicit LocalServer(std::string video = "");
  ~LocalServer();
  LocalServer(const LocalServer&) = delete;
  LocalServer& operator=(const LocalServer&) = delete;
  std::string url() const;

 private:
  void serveOnce();

  int fd_ = -1;
  int port_ = 0;
  std::string video_;
  std::thread server_;
};

// Runs a shell command, its output discarded; its exit code.
int runShell(const std::string& command);

// Makes a video with FFmpeg's command-line tool: `ffmpeg -v error -y ARGUMENTS`; false when it
// failed or ffmpeg is missing (tests then fail: scripts/install-deps.sh installs it).
bool ffmpeg(const std::string& arguments);

// The DAVIS 2016 dataset folder (<sequence>/frames, <sequence>/masks): $MOVSEG_DATA/davis2016,
// or the shared data next to the source tree; "" when it is not there (tests then skip).
std::string davisDataset();

// The folder of one of its sequences (frames/, masks/); "" when it is not there.
std::string davisSequence(const std::string& name);

// The first `count` frame files of that sequence, in order; none when it is not there.
std::vector<std::string> davisFrames(const std::string& name, size_t count);

}  // namespace movseg::test

#include <cstdint>

#include <opencv2/core.hpp>

#include "movseg/fields.h"
#include "movseg/params.h"

namespace movseg::test {

// A richly textured BGR image (smoothed noise at several scales), the same for the same seed.
cv::Mat texture(cv::Size size, std::uint64_t seed);

// The same, in grey (CV_8U).
cv::Mat greyTexture(cv::Size size, std::uint64_t seed);

// Maximum distance between the images of the four corners of a w x h frame under two models.
double cornerError(const cv::Matx33d& estimated, const cv::Matx33d& truth, cv::Size size);

// The default parameters with `method` chosen: for tests that read one pipeline's stages.
Params withMethod(Method method);

// A valid value of `field` (movseg/fields.h) other than its value in `params`, as text.
std::string otherParamValue(const FieldInfo& field, const Params& params);

}  // namespace movseg::test
