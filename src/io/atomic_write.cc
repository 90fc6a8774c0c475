#include "io/atomic_write.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace movseg {
namespace {

void writeBytesAtomic(const std::string& path, const char* data, size_t size) {
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(data, static_cast<std::streamsize>(size));
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      throw std::runtime_error("cannot write '" + path + "'");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
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

}  // namespace movseg
