// The image files of a folder for the drivers that run under valgrind (bench/*_driver.cc): they
// link the library and OpenCV's image codecs only, not the tools' io (src/io/frame_source.h's
// listImages), whose FFmpeg start-up code stops valgrind.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

inline std::vector<std::string> imagesIn(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".jpg" || ext == ".png") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}
