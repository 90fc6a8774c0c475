// Where frames come from: a video file or stream URL (anything OpenCV's FFmpeg backend opens),
// a folder of images sorted by name, or a camera index.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Next frame as decoded (any depth and channel count); false at the end. Throws
  // std::runtime_error when a frame cannot be read (corrupt image file).
  virtual bool read(cv::Mat* frame) = 0;
  // Frames in total when known up front (folders, most files), else -1.
  virtual int frameCount() const = 0;
  // Name of the current frame for messages, e.g. "frames/00012.png" or "frame 12".
  virtual std::string describe() const = 0;

  // Opens `input`: an existing folder, an existing file, a string of digits (camera index) or a
  // URL with "://". Throws std::runtime_error with a one-line reason when it cannot be opened.
  static std::unique_ptr<FrameSource> open(const std::string& input);
};

// The image files of a folder (by extension, case-insensitive), sorted by name.
std::vector<std::string> listImages(const std::string& folder);

// cv::imread, but an empty Mat for every file it cannot decode: OpenCV throws instead when a
// header claims a size beyond its limits.
cv::Mat decodeImage(const std::string& path, int flags);

}  // namespace movseg
