#include "video_input.h"

#include <chrono>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "fuzz_input.h"
#include "io/frame_source.h"
#include "movseg/segmenter.h"

namespace movseg::fuzz {
namespace {

constexpr int kMaxFramesRead = 8;
constexpr std::int64_t kMaxPixels = 1 << 20;  // a header may claim any size

}  // namespace

void runVideoInput(const std::uint8_t* data, std::size_t size, const std::string& path) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  std::unique_ptr<FrameSource> source;
  try {
    source = FrameSource::open(path, DecoderLimits{std::chrono::seconds(10), nullptr, kMaxPixels});
  } catch (const std::runtime_error&) {
    return;  // not a video it can open: said in one line
  }
  Segmenter segmenter;
  cv::Mat frame;
  for (int i = 0; i < kMaxFramesRead; ++i) {
    bool got = false;
    try {
      got = source->read(&frame);
    } catch (const std::runtime_error&) {
      break;
    }
    if (!got) break;
    require(frame.type() == CV_8UC3 && !frame.empty(), "a frame that is not 8-bit BGR");
    require(segmenter.process(frame).mask.size() == frame.size(), "a mask of the wrong size");
  }
  const SourceReport report = source->report();
  require(report.decode_errors == 0 || !report.last_error.empty(), "a decode error without its text");
}

}  // namespace movseg::fuzz
