#include "readers_input.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "eval/dataset.h"
#include "fuzz_input.h"
#include "io/frame_source.h"
#include "movseg/segmenter.h"

namespace movseg::fuzz {
namespace {
namespace fs = std::filesystem;

// Decoded frames larger than this are read but not segmented: the segmenter target covers
// process(), this one covers the files.
constexpr int kMaxSegmentedPixels = 256 * 256;
constexpr int kMaxFiles = 6;
constexpr int kMaxFileBytes = 4096;

struct Layout {
  std::string masks;   // relative to the sequence folder
  std::string frames;  // plain ground truth has none: "frames" is then just another folder
};

// The folders of each format (src/eval/dataset.h), SegTrack under both spellings.
const Layout kLayouts[] = {
    {".", "frames"}, {"masks", "frames"}, {"ground-truth", "."}, {"GroundTruth", "."},
    {"groundtruth", "input"},
};
const GtFormat kFormats[] = {GtFormat::kAuto, GtFormat::kPlain, GtFormat::kDavis,
                             GtFormat::kSegtrack, GtFormat::kCdnet};

// Names made of digits, a few letters and separators, with an image extension or not: frame
// numbers, duplicates, hidden files and names without digits all come up.
std::string fuzzedName(FuzzInput& in) {
  static const char kAlphabet[] = "0123456789_-. aZ";
  static const char* const kExtensions[] = {".png", ".PNG", ".jpg", ".bmp", ".pgm",
                                            ".ppm", ".tif", ".webp", ".txt", ""};
  std::string name;
  for (int n = in.range(0, 12); n > 0; --n) name += kAlphabet[in.range(0, 15)];
  return name + kExtensions[in.range(0, 9)];
}

void writeFile(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

// Runs `read`; a std::runtime_error is the one honest answer to a bad file.
void expectingBadFiles(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::runtime_error&) {
  }
}

void checkMask(const cv::Mat& mask, const cv::Mat& ignore) {
  require(mask.type() == CV_8UC1, "mask read as other than CV_8U");
  require(cv::countNonZero((mask != 0) & (mask != 255)) == 0,
          "mask read with values other than 0/255");
  require(ignore.empty() || ignore.size() == mask.size(), "ignore region of another size");
}

void checkScore(const SequenceScore& score) {
  for (const FrameScore& f : score.frames) {
    require(std::isfinite(f.j) && std::isfinite(f.f) && std::isfinite(f.error_rate),
            "non-finite score");
  }
}

void readGroundTruth(const std::string& gt, GtFormat format, const std::string& pred) {
  for (const GtSequence& sequence : loadGroundTruth(gt, format)) {
    for (const GtFrame& frame : sequence.frames) {
      expectingBadFiles([&] {
        cv::Mat ignore;
        const cv::Mat mask = readGtMask(sequence, frame, &ignore);
        checkMask(mask, ignore);
      });
    }
    expectingBadFiles([&] { checkScore(scoreSequence(sequence, predictionDir(sequence, pred))); });
  }
}

void segmentFrames(const std::string& frames) {
  const std::unique_ptr<FrameSource> source = FrameSource::open(frames);
  Segmenter segmenter;
  cv::Mat frame;
  while (source->read(&frame)) {
    if (frame.total() > static_cast<size_t>(kMaxSegmentedPixels)) continue;
    try {
      const Result result = segmenter.process(frame);
      require(result.mask.size() == frame.size(), "mask of the wrong size");
    } catch (const std::invalid_argument&) {  // a decoded image of unsupported type
    }
  }
}

}  // namespace

void runReadersInput(const std::uint8_t* data, std::size_t size, const std::string& scratch) {
  fs::remove_all(scratch);
  FuzzInput in(data, size);
  const Layout& layout = kLayouts[in.range(0, 4)];
  const GtFormat format = kFormats[in.range(0, 4)];
  const fs::path gt = fs::path(scratch) / "gt", pred = fs::path(scratch) / "pred";
  // One sequence, or a dataset folder holding it (and its predictions in pred/seq/).
  const bool dataset = in.flag();
  const fs::path sequence = dataset ? gt / "seq" : gt;
  const fs::path predictions = dataset ? pred / "seq" : pred;
  fs::create_directories(sequence);
  fs::create_directories(predictions);
  for (int n = in.range(1, kMaxFiles); n > 0; --n) {
    fs::path folder;
    switch (in.range(0, 3)) {
      case 0: folder = sequence / layout.masks; break;
      case 1: folder = sequence / layout.frames; break;
      case 2: folder = predictions; break;
      default: folder = sequence; break;  // temporalROI.txt and strays
    }
    const std::string name = in.range(0, 7) == 0 ? "temporalROI.txt" : fuzzedName(in);
    writeFile(folder / name, in.bytes(static_cast<size_t>(in.range(0, kMaxFileBytes))));
  }
  expectingBadFiles([&] { readGroundTruth(gt.string(), format, pred.string()); });
  expectingBadFiles([&] { segmentFrames((sequence / layout.frames).string()); });
}

}  // namespace movseg::fuzz
