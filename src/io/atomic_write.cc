#include "io/atomic_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace movseg {
namespace {
namespace fs = std::filesystem;

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

// Renames `temporary` over `target`, the file a write to `path` goes to.
void renameOver(const std::string& temporary, const std::string& target, const std::string& path) {
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

// Where a write to a path goes.
struct Target {
  std::string path;       // the path, or the file a symlink there points to (through every link)
  bool in_place = false;  // an existing device, FIFO or open descriptor: written directly, never
                          // renamed over
  int descriptor = -1;    // /dev/stdout and the like: this process's descriptor, written through
};

// The descriptor a path names through /proc (/dev/stdout -> /proc/self/fd/1), or -1. Written
// through it, the output shares the descriptor's offset with what the process writes there.
int ownDescriptorOf(const fs::path& path) {
  const std::string text = path.lexically_normal().string();
  const std::string prefixes[] = {"/proc/self/fd/", "/dev/fd/",
                                  "/proc/" + std::to_string(::getpid()) + "/fd/"};
  for (const std::string& prefix : prefixes) {
    if (text.rfind(prefix, 0) != 0) continue;
    const std::string number = text.substr(prefix.size());
    if (number.empty() || number.size() > 9 ||
        !std::all_of(number.begin(), number.end(), [](unsigned char c) { return std::isdigit(c); })) {
      return -1;
    }
    return std::stoi(number);
  }
  return -1;
}

// A folder is refused here: renaming a file over it would fail only once the work is done.
Target resolveTarget(const std::string& path) {
  std::error_code error;
  fs::path target = path;
  for (int links = 0; links < 40 && fs::is_symlink(target, error); ++links) {
    const int descriptor = ownDescriptorOf(target);
    if (descriptor >= 0) return {path, true, descriptor};
    const fs::path link = fs::read_symlink(target, error);
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const fs::file_status status = fs::status(path, error);  // as open() sees it
  if (fs::is_directory(status)) throw writeError(path, EISDIR);
  return {target.string(), fs::exists(status) && !fs::is_regular_file(status)};
}

// Opens an existing device or FIFO for writing, or a copy of the process's own descriptor. A
// FIFO without a reader is refused at once (ENXIO) rather than waited for: a blocked open()
// would not even end on SIGINT.
int openInPlace(const Target& target, const std::string& path) {
  if (target.descriptor >= 0) {
    // What the process printed there before comes first: its streams' buffers go out now.
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    const int fd = ::fcntl(target.descriptor, F_DUPFD_CLOEXEC, 0);
    if (fd < 0) throw writeError(path, errno);
    return fd;
  }
  const int fd = ::open(target.path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 && errno == ENXIO) {
    throw std::runtime_error("cannot write '" + path + "': no process reads the FIFO");
  }
  if (fd < 0) throw writeError(path, errno);
  // Writes then wait for a slow reader, as they would for a file on a slow disk.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

// Writes all of `data` to `fd` and closes it; the errno of the failure, or 0.
int writeAndClose(int fd, const char* data, size_t size) {
  int error = writeAll(fd, data, size);
  if (::close(fd) != 0 && error == 0) error = errno;
  return error;
}

}  // namespace

std::string temporaryPath(const std::string& path, bool keep_extension) {
  constexpr size_t kMaxName = 255;  // NAME_MAX on Linux's file systems
  const fs::path p(path);
  const std::string extension = keep_extension ? p.extension().string() : "";
  std::string stem = keep_extension ? p.stem().string() : p.filename().string();
  const size_t room =
      kMaxName - (sizeof kTemporaryMark - 1) - std::min(extension.size(), kMaxName / 2);
  if (stem.size() > room) stem.resize(room);
  return (p.parent_path() / (stem + kTemporaryMark + extension)).string();
}

namespace {

void writeBytesAtomic(const std::string& path, const char* data, size_t size) {
  const Target target = resolveTarget(path);
  if (target.in_place) {
    const int error = writeAndClose(openInPlace(target, path), data, size);
    if (error != 0) throw writeError(path, error);
    return;
  }
  const std::string temporary = temporaryPath(target.path);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw writeError(path, errno);
  const int error = writeAndClose(fd, data, size);
  if (error != 0) {
    std::remove(temporary.c_str());
    throw writeError(path, error);
  }
  renameOver(temporary, target.path, path);
}

}  // namespace

void writeImageAtomic(const std::string& path, const cv::Mat& image) {
  std::vector<uchar> bytes;
  const std::string ext = fs::path(path).extension().string();
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

void checkOutputFile(const std::string& path) {
  const Target target = resolveTarget(path);
  if (target.in_place) return;  // opening a FIFO to try it would give its reader an end of file
  const std::string temporary = temporaryPath(target.path);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw writeError(path, errno);
  ::close(fd);
  std::remove(temporary.c_str());
}

void makeOutputFolder(const std::string& path) {
  std::error_code error;
  fs::create_directories(path, error);
  if (error || !fs::is_directory(path)) {
    throw std::runtime_error("cannot create output folder '" + path + "'" +
                             (error ? ": " + error.message() : ""));
  }
}

fs::path folderPath(const std::string& path) {
  const fs::path normal = fs::absolute(path).lexically_normal();
  return normal.has_filename() ? normal : normal.parent_path();
}

std::string frameFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%05d.png", index);
  return name;
}

bool isFrameFileName(const std::string& name) {
  const fs::path path(name);
  const std::string stem = path.stem().string();
  return path.extension() == ".png" && stem.size() >= 5 &&
         std::all_of(stem.begin(), stem.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::vector<std::string> frameFilesIn(const std::string& folder) {
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    if (isFrameFileName(entry.path().filename().string())) files.push_back(entry.path().string());
  }
  return files;
}

LineFile::LineFile(std::string path) : path_(std::move(path)) {
  const Target target = resolveTarget(path_);
  target_ = target.path;
  in_place_ = target.in_place;
  if (in_place_) {
    fd_ = openInPlace(target, path_);
    return;
  }
  fd_ = ::open(temporaryPath(target_).c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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
    if (!in_place_ && ::ftruncate(fd_, size_) == 0) ::lseek(fd_, size_, SEEK_SET);
    throw writeError(path_, error);
  }
  size_ += static_cast<long long>(text.size());
}

void LineFile::close() {
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw writeError(path_, errno);
  if (!in_place_) renameOver(temporaryPath(target_), target_, path_);
}

}  // namespace movseg
