#include "io/atomic_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace movseg {
namespace {

std::runtime_error writeError(const std::string& path, int error) {
  return std::runtime_error("cannot write '" + path + "': " + std::strerror(error));
}

// Writes all of `data` to `fd`; the errno of the failure, or 0.
int writeAll(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? errno : ENOSPC;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return 0;
}

void renameOver(const std::string& temporary, const std::string& path) {
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

void writeBytesAtomic(const std::string& path, const char* data, size_t size) {
  const std::string temporary = path + ".part";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw writeError(path, errno);
  int error = writeAll(fd, data, size);
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    std::remove(temporary.c_str());
    throw writeError(path, error);
  }
  renameOver(temporary, path);
}

}  // namespace

void writeImageAtomic(const std::string& path, const cv::Mat& image) {
  std::vector<uchar> bytes;
  const std::string ext = std::filesystem::path(path).extension().string();
  bool encoded = false;
  try {
    encoded = cv::imencode(ext.empty() ? ".png" : ext, image, bytes);
  } catch (const cv::Exception&) {  // unknown extension or unsupported image type
  }
  if (!encoded) throw std::runtime_error("cannot encode '" + path + "'");
  writeBytesAtomic(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void writeTextAtomic(const std::string& path, const std::string& text) {
  writeBytesAtomic(path, text.data(), text.size());
}

void makeOutputFolder(const std::string& path) {
  std::error_code error;
  std::filesystem::create_directories(path, error);
  if (error || !std::filesystem::is_directory(path)) {
    throw std::runtime_error("cannot create output folder '" + path + "'" +
                             (error ? ": " + error.message() : ""));
  }
}

std::string frameFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%05d.png", index);
  return name;
}

LineFile::LineFile(std::string path) : path_(std::move(path)) {
  fd_ = ::open((path_ + ".part").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw writeError(path_, errno);
}

LineFile::~LineFile() {
  if (fd_ >= 0) ::close(fd_);
}

void LineFile::append(const std::string& line) {
  const std::string text = line + '\n';
  const int error = writeAll(fd_, text.data(), text.size());
  if (error != 0) {
    // Cut the partial line off again, so that the file still ends with a whole line.
    if (::ftruncate(fd_, size_) == 0) ::lseek(fd_, size_, SEEK_SET);
    throw writeError(path_, error);
  }
  size_ += static_cast<long long>(text.size());
}

void LineFile::close() {
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw writeError(path_, errno);
  renameOver(path_ + ".part", path_);
}

}  // namespace movseg
