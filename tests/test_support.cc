#include "test_support.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>

#include "io/frame_source.h"

namespace movseg::test {

#ifdef __SANITIZE_THREAD__
// ThreadSanitizer cannot see the hand-offs inside OpenCV's thread pool (TBB, not instrumented)
// and reports them as races; under it OpenCV runs on the calling threads, and what TSan checks
// is movseg's own threads (docs/reliability.md).
[[maybe_unused]] const bool kOpenCvOnCallingThreads = [] {
  cv::setNumThreads(1);
  return true;
}();
#endif

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

namespace {

CommandResult runCommand(const std::string& command_line) {
  CommandResult result;
  const std::string command = command_line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace

CommandResult runCli(const std::string& arguments) {
  return runCommand(std::string(MOVSEG_CLI_PATH) + " " + arguments);
}

CommandResult runCliWithFileLimit(long bytes, const std::string& arguments) {
  const std::string limit = std::to_string(bytes);
  return runCommand("prlimit --fsize=" + limit + ":" + limit + " " + MOVSEG_CLI_PATH + " " + arguments);
}

void expectOneLineError(const CommandResult& r, const std::string& needle, int code) {
  EXPECT_EQ(r.exit_code, code) << r.output;
  EXPECT_EQ(r.output.rfind("movseg: error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
}

pid_t startCli(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv{const_cast<char*>(MOVSEG_CLI_PATH)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, MOVSEG_CLI_PATH, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

LocalServer::LocalServer(std::string video) : video_(std::move(video)) {
  fd_ = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
  listen(fd_, 4);
  if (!video_.empty()) server_ = std::thread([this] { serveOnce(); });
}

LocalServer::~LocalServer() {
  shutdown(fd_, SHUT_RDWR);
  close(fd_);
  if (server_.joinable()) server_.join();
}

std::string LocalServer::url() const {
  return "http://127.0.0.1:" + std::to_string(port_) + "/video";
}

void LocalServer::serveOnce() {
  const int client = accept(fd_, nullptr, nullptr);
  if (client < 0) return;
  const std::string head = "HTTP/1.0 200 OK\r\nContent-Type: application/octet-stream\r\n\r\n";
  send(client, head.data(), head.size(), MSG_NOSIGNAL);
  send(client, video_.data(), video_.size(), MSG_NOSIGNAL);
  char ignored[256];
  while (recv(client, ignored, sizeof ignored, 0) > 0) {}  // until the reader hangs up
  close(client);
}

int runShell(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool ffmpeg(const std::string& arguments) {
  return runShell("ffmpeg -nostdin -hide_banner -v error -y " + arguments) == 0;
}

std::string davisDataset() {
  const char* data = std::getenv("MOVSEG_DATA");
  const std::string root = data != nullptr ? data : std::string(MOVSEG_SOURCE_DIR) + "/../shared/data";
  const std::string folder = root + "/davis2016";
  return std::filesystem::is_directory(folder) ? folder : "";
}

std::string davisSequence(const std::string& name) {
  const std::string dataset = davisDataset();
  const std::string folder = dataset + "/" + name;
  return !dataset.empty() && std::filesystem::is_directory(folder + "/frames") ? folder : "";
}

std::vector<std::string> davisFrames(const std::string& name, size_t count) {
  const std::string folder = davisSequence(name);
  if (folder.empty()) return {};
  std::vector<std::string> files = listImages(folder + "/frames");
  files.resize(std::min(files.size(), count));
  return files;
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

cv::Mat greyTexture(cv::Size size, std::uint64_t seed) {
  cv::Mat grey;
  cv::cvtColor(texture(size, seed), grey, cv::COLOR_BGR2GRAY);
  return grey;
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

Params withMethod(Method method) {
  Params params;
  params.method = method;
  return params;
}

std::string otherParamValue(const FieldInfo& field, const Params& params) {
  const FieldValue value = paramValue(params, field.name);
  switch (field.type) {
    case FieldType::kBool:
      return std::get<bool>(value) ? "false" : "true";
    case FieldType::kChoice: {
      const std::vector<std::string>& names = field.choices;
      const auto at = std::find(names.begin(), names.end(), std::get<std::string>(value));
      return names[static_cast<size_t>(at - names.begin() + 1) % names.size()];
    }
    case FieldType::kInt: {
      const int v = std::get<int>(value), step = std::max(field.step, 1);
      return std::to_string(v + step <= field.max ? v + step : v - step);
    }
    case FieldType::kUnsigned:
      return std::to_string(std::get<std::uint64_t>(value) + 1);
    case FieldType::kReal: {
      const double v = std::get<double>(value);
      return toText(v < field.max ? v + (field.max - v) / 8 : v - (v - field.min) / 8);
    }
    case FieldType::kMatrix:
      break;
  }
  ADD_FAILURE() << field.name << ": no other value";
  return "";
}

}  // namespace movseg::test
