#include "io/frame_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

namespace movseg {
namespace fs = std::filesystem;
namespace {

bool isImageFile(const fs::path& path) {
  static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif",
                                            ".tiff", ".ppm", ".pgm", ".webp"};
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

class ImageFolderSource : public FrameSource {
 public:
  explicit ImageFolderSource(const std::string& folder) : files_(listImages(folder)) {
    if (files_.empty()) throw std::runtime_error("no images in folder '" + folder + "'");
  }
  bool read(cv::Mat* frame) override {
    if (next_ >= files_.size()) return false;
    current_ = files_[next_++];
    *frame = decodeImage(current_, cv::IMREAD_UNCHANGED);
    if (frame->empty()) throw std::runtime_error("cannot decode image '" + current_ + "'");
    return true;
  }
  int frameCount() const override { return static_cast<int>(files_.size()); }
  std::string describe() const override { return current_; }

 private:
  std::vector<std::string> files_;
  size_t next_ = 0;
  std::string current_;
};

class VideoSource : public FrameSource {
 public:
  VideoSource(const std::string& name, cv::VideoCapture capture)
      : name_(name), capture_(std::move(capture)) {
    const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
    count_ = count > 0 ? static_cast<int>(count) : -1;
  }
  bool read(cv::Mat* frame) override {
    if (!capture_.read(*frame) || frame->empty()) return false;
    ++index_;
    return true;
  }
  int frameCount() const override { return count_; }
  std::string describe() const override {
    return name_ + " frame " + std::to_string(index_ - 1);
  }

 private:
  std::string name_;
  cv::VideoCapture capture_;
  int count_ = -1;
  int index_ = 0;
};

bool isCameraIndex(const std::string& input) {
  return !input.empty() && input.size() <= 3 &&
         std::all_of(input.begin(), input.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

std::vector<std::string> listImages(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file() && isImageFile(entry.path())) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

cv::Mat decodeImage(const std::string& path, int flags) {
  try {
    return cv::imread(path, flags);
  } catch (const cv::Exception&) {
    return cv::Mat();
  }
}

std::unique_ptr<FrameSource> FrameSource::open(const std::string& input) {
  std::error_code error;
  if (fs::is_directory(input, error)) return std::make_unique<ImageFolderSource>(input);
  cv::VideoCapture capture;
  if (fs::is_regular_file(input, error)) {
    if (isImageFile(input)) throw std::runtime_error("'" + input + "' is a single image, not a video");
    capture.open(input, cv::CAP_FFMPEG);
  } else if (isCameraIndex(input)) {
    capture.open(std::stoi(input));
  } else if (input.find("://") != std::string::npos) {
    capture.open(input, cv::CAP_FFMPEG);
  } else {
    throw std::runtime_error("cannot open '" + input + "': no such file or folder");
  }
  if (!capture.isOpened()) throw std::runtime_error("cannot open video '" + input + "'");
  return std::make_unique<VideoSource>(input, std::move(capture));
}

}  // namespace movseg
