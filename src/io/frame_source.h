// Where frames come from, one input grammar for every command: a video file or stream URL
// (decoded by FFmpeg), a folder of images in number order, a sequence folder holding frames/
// (DAVIS, `movseg synth`), a printf pattern of numbered images (frames/%05d.jpg), or a camera
// index.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "io/video_decoder.h"

namespace movseg {

// What a source knows about its stream besides the frames.
struct SourceReport {
  int expected_frames = -1;   // frames in total when known up front (folders, most files)
  bool exact_count = true;    // false: expected_frames is estimated from a duration
  double duration_seconds = -1;  // that duration when the count is estimated, else -1
  double reached_seconds = -1;   // the last frame's time from the start, -1 when unknown
  double fps = 0;             // the frame rate it says it runs at; 0 when it does not say
  int decode_errors = 0;      // errors the decoder reported so far
  std::string last_error;     // the last one, in one line
  bool timed_out = false;     // a read() gave up at the timeout: the stream stalled
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Next frame as decoded (any depth and channel count); false at the end. Throws
  // std::runtime_error when a frame cannot be read (corrupt image file).
  virtual bool read(cv::Mat* frame) = 0;
  virtual SourceReport report() const = 0;
  // Name of the current frame for messages, e.g. "frames/00012.png" or "clip.mp4 frame 12".
  virtual std::string describe() const = 0;

  // Opens `input` (the grammar above; a path that exists wins over a pattern or a camera
  // index). Throws std::runtime_error with a one-line reason when it cannot be opened.
  static std::unique_ptr<FrameSource> open(const std::string& input,
                                           const DecoderLimits& limits = {});
};

// The file or folder on disk that `input` reads (for a pattern, its folder); "" for a camera or
// a URL. Outputs must stay out of it.
std::string inputPath(const std::string& input);

// Whether name a comes before b with the runs of digits in them compared as numbers: 2.png
// before 10.png, as a camera or a script that does not pad its numbers means them (and as
// `eval` matches masks to frames); zero-padded names keep their order by name.
bool inNumberOrder(const std::string& a, const std::string& b);

// The image files of a folder (by extension, case-insensitive; hidden ones, such as macOS's
// `._00002.png`, are not frames), in number order (inNumberOrder).
std::vector<std::string> listImages(const std::string& folder);

// cv::imread, but an empty Mat for every file it cannot decode, and nothing printed: OpenCV
// throws instead when a header claims a size beyond its limits; a damaged JPEG (data cut short
// by an interrupted copy, a bad Huffman code), which libjpeg decodes with a warning on stderr
// and whatever the damage leaves in its rows, is not decoded (io/jpeg_file.h, which decodes the
// JPEG frames read unchanged); nor is a PNG whose chunks are cut short or corrupt, of which
// libpng would print its error on stderr; nor a file that does not begin as one of the formats
// listImages() reads (OpenCV would pick a decoder by its bytes: DICOM's aborted the process);
// nor anything but a regular file (a FIFO would block).
cv::Mat decodeImage(const std::string& path, int flags);

}  // namespace movseg
