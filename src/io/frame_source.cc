#include "io/frame_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <new>
#include <stdexcept>
#include <vector>

#include <zlib.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/text.h"
#include "io/image_limits.h"
#include "io/jpeg_file.h"
#include "io/png_file.h"

namespace movseg {
namespace fs = std::filesystem;
namespace {

bool isImageFile(const fs::path& path) {
  static const char* const kExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif",
                                            ".tiff", ".ppm", ".pgm", ".webp"};
  const std::string ext = lowercase(path.extension().string());
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

// Image files read in order: a folder's, or a pattern's.
class ImageListSource : public FrameSource {
 public:
  explicit ImageListSource(std::vector<std::string> files) : files_(std::move(files)) {}
  bool read(cv::Mat* frame) override {
    if (next_ >= files_.size()) return false;
    current_ = files_[next_++];
    *frame = decodeImage(current_, cv::IMREAD_UNCHANGED);
    if (frame->empty()) throw std::runtime_error("cannot decode image '" + current_ + "'");
    return true;
  }
  SourceReport report() const override {
    SourceReport report;
    report.expected_frames = static_cast<int>(files_.size());
    return report;
  }
  std::string describe() const override { return current_; }

 private:
  std::vector<std::string> files_;
  size_t next_ = 0;
  std::string current_;
};

class VideoSource : public FrameSource {
 public:
  VideoSource(const std::string& name, const DecoderLimits& limits) : name_(name), decoder_(name, limits) {}
  bool read(cv::Mat* frame) override {
    if (!decoder_.read(frame)) return false;
    ++index_;
    return true;
  }
  SourceReport report() const override {
    SourceReport report;
    report.expected_frames = decoder_.expectedFrames();
    report.exact_count = decoder_.exactCount();
    report.duration_seconds = decoder_.durationSeconds();
    report.reached_seconds = decoder_.reachedSeconds();
    report.fps = decoder_.fps();
    report.decode_errors = decoder_.errors();
    report.last_error = decoder_.lastError();
    report.timed_out = decoder_.timedOut();
    return report;
  }
  std::string describe() const override { return name_ + " frame " + std::to_string(index_ - 1); }

 private:
  std::string name_;
  VideoDecoder decoder_;
  int index_ = 0;
};

class CameraSource : public FrameSource {
 public:
  explicit CameraSource(int index) : index_(index), capture_(index) {
    if (!capture_.isOpened()) throw std::runtime_error("cannot open camera " + std::to_string(index));
  }
  bool read(cv::Mat* frame) override {
    if (!capture_.read(*frame) || frame->empty()) return false;
    ++frames_;
    return true;
  }
  SourceReport report() const override {
    SourceReport report;
    report.fps = capture_.get(cv::CAP_PROP_FPS);
    return report;
  }
  std::string describe() const override {
    return "camera " + std::to_string(index_) + " frame " + std::to_string(frames_ - 1);
  }

 private:
  int index_;
  cv::VideoCapture capture_;
  int frames_ = 0;
};

bool isCameraIndex(const std::string& input) {
  return !input.empty() && input.size() <= 3 &&
         std::all_of(input.begin(), input.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool isUrl(const std::string& input) { return input.find("://") != std::string::npos; }

// A printf pattern of numbered files, "frames/%05d.jpg": one %d with an optional zero-padded
// width, "%%" for a percent sign. Expanded by hand: the pattern is never a format string.
struct FramePattern {
  std::string prefix, suffix;
  int width = 0;
  bool zeros = false;

  std::string path(int number) const {
    std::string digits = std::to_string(number);
    if (static_cast<int>(digits.size()) < width) {
      digits.insert(0, static_cast<size_t>(width) - digits.size(), zeros ? '0' : ' ');
    }
    return prefix + digits + suffix;
  }
};

// Fills *pattern when `input` holds exactly one integer conversion.
bool parsePattern(const std::string& input, FramePattern* pattern) {
  std::string* part = &pattern->prefix;
  int conversions = 0;
  for (size_t i = 0; i < input.size(); ++i) {
    if (input[i] != '%') {
      *part += input[i];
      continue;
    }
    if (i + 1 < input.size() && input[i + 1] == '%') {
      *part += input[++i];
      continue;
    }
    size_t j = i + 1;
    pattern->zeros = j < input.size() && input[j] == '0';
    std::string width;
    while (j < input.size() && std::isdigit(static_cast<unsigned char>(input[j]))) width += input[j++];
    if (j >= input.size() || input[j] != 'd' || width.size() > 2) return false;
    pattern->width = width.empty() ? 0 : std::stoi(width);
    part = &pattern->suffix;
    ++conversions;
    i = j;
  }
  return conversions == 1;
}

// The files of a pattern: from the first number in 0..4 that exists (as FFmpeg's image2
// reader starts) up to the first number missing after it.
std::vector<std::string> patternFiles(const FramePattern& pattern) {
  std::error_code error;
  int number = 0;
  while (number < 5 && !fs::is_regular_file(pattern.path(number), error)) ++number;
  std::vector<std::string> files;
  while (fs::is_regular_file(pattern.path(number), error)) files.push_back(pattern.path(number++));
  return files;
}

// The folder itself when it holds images, else its frames/ when there is one (a sequence).
std::string imageFolder(const std::string& folder) {
  const std::string frames = (fs::path(folder) / "frames").string();
  std::error_code error;
  return listImages(folder).empty() && fs::is_directory(frames, error) ? frames : folder;
}

std::vector<std::string> folderImages(const std::string& folder) {
  std::vector<std::string> files = listImages(imageFolder(folder));
  if (files.empty()) throw std::runtime_error("no images in folder '" + folder + "' (nor in its frames/)");
  return files;
}

}  // namespace

bool inNumberOrder(const std::string& a, const std::string& b) {
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (!digit(a[i]) || !digit(b[j])) {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i, ++j;
      continue;
    }
    // Two runs of digits: by value (more significant digits, then the digits themselves), the
    // leading zeros left aside.
    const size_t a_end = std::find_if_not(a.begin() + i, a.end(), digit) - a.begin();
    const size_t b_end = std::find_if_not(b.begin() + j, b.end(), digit) - b.begin();
    while (i + 1 < a_end && a[i] == '0') ++i;
    while (j + 1 < b_end && b[j] == '0') ++j;
    if (a_end - i != b_end - j) return a_end - i < b_end - j;
    const int order = a.compare(i, a_end - i, b, j, b_end - j);
    if (order != 0) return order < 0;
    i = a_end, j = b_end;
  }
  if (i < a.size() || j < b.size()) return j < b.size();  // a prefix of the other comes first
  return a < b;  // equal in value (001.png, 1.png): by name, so the order is total
}

std::vector<std::string> listImages(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const bool hidden = entry.path().filename().string().front() == '.';  // macOS's ._00002.png
    if (!hidden && entry.is_regular_file() && isImageFile(entry.path())) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end(), inNumberOrder);
  return files;
}

namespace {

std::uint32_t bigEndian32(const unsigned char* bytes) {
  return std::uint32_t{bytes[0]} << 24 | std::uint32_t{bytes[1]} << 16 |
         std::uint32_t{bytes[2]} << 8 | bytes[3];
}

// The bytes of a PNG image's rows once inflated (a filter byte and the packed pixels per row),
// each of Adam7's seven passes in turn when `interlaced`.
std::uint64_t inflatedSize(std::uint64_t width, std::uint64_t height, unsigned bits_per_pixel,
                           bool interlaced) {
  const auto rows = [&](std::uint64_t w, std::uint64_t h) -> std::uint64_t {
    return w == 0 || h == 0 ? 0 : h * (1 + (w * bits_per_pixel + 7) / 8);
  };
  if (!interlaced) return rows(width, height);
  constexpr int kX[7] = {0, 4, 0, 2, 0, 1, 0}, kY[7] = {0, 0, 4, 0, 2, 0, 1};
  constexpr int kStepX[7] = {8, 8, 4, 4, 2, 2, 1}, kStepY[7] = {8, 8, 8, 4, 4, 2, 2};
  std::uint64_t size = 0;
  for (int pass = 0; pass < 7; ++pass) {
    const auto across = [](std::uint64_t n, int start, int step) -> std::uint64_t {
      return n > static_cast<std::uint64_t>(start) ? (n - start + step - 1) / step : 0;
    };
    size += rows(across(width, kX[pass], kStepX[pass]), across(height, kY[pass], kStepY[pass]));
  }
  return size;
}

// Bits per pixel of a PNG colour type (0 grey, 2 RGB, 3 palette, 4 grey and alpha, 6 RGBA) at
// `depth` bits a sample; 0 for a type that does not exist.
unsigned bitsPerPixel(unsigned colour_type, unsigned depth) {
  switch (colour_type) {
    case 0: case 3: return depth;
    case 2: return 3 * depth;
    case 4: return 2 * depth;
    case 6: return 4 * depth;
    default: return 0;
  }
}

// Whether the IDAT chunks' data (`parts`) inflate to at least `expected` bytes: libpng stops
// with "Not enough image data" otherwise, printed on stderr.
bool inflatesTo(const std::vector<std::pair<const uchar*, std::uint32_t>>& parts,
                std::uint64_t expected) {
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) return false;
  unsigned char scratch[1 << 15];
  std::uint64_t produced = 0;
  int status = Z_OK;
  for (const auto& [data, length] : parts) {
    stream.next_in = const_cast<uchar*>(data);
    stream.avail_in = length;
    while (status == Z_OK && stream.avail_in > 0) {
      stream.next_out = scratch;
      stream.avail_out = sizeof scratch;
      status = inflate(&stream, Z_NO_FLUSH);
      produced += sizeof scratch - stream.avail_out;
      if (status == Z_BUF_ERROR) {  // no progress with this chunk's data: on to the next one
        status = Z_OK;
        break;
      }
      if (produced >= expected) break;
    }
    if (status != Z_OK || produced >= expected) break;
  }
  inflateEnd(&stream);
  return produced >= expected;
}

// A PNG file (it starts with the PNG signature) that libpng would refuse: its chunks do not run
// whole up to IEND (a file cut short), a critical chunk's CRC does not match (libpng only warns
// of an ancillary one's, and decodes the image), the header's size is beyond libpng's default
// limits (1,000,000 pixels a side, which OpenCV keeps), or its image data inflates to fewer
// bytes than its rows need (a writer that stopped early, the file then closed properly). libpng
// prints each such error on stderr before OpenCV sees it, and the CLI's errors are one line.
bool isDamagedPng(const std::vector<uchar>& file) {
  constexpr std::uint32_t kMaxSide = 1000000;
  if (!isPng(file)) return false;
  std::uint64_t expected = 0;
  std::vector<std::pair<const uchar*, std::uint32_t>> image_data;  // the IDAT chunks' data
  for (size_t at = 8;; ) {
    if (file.size() - at < 12) return true;  // a chunk's length, type and CRC at least
    const std::uint32_t length = bigEndian32(&file[at]);
    if (length > file.size() - at - 12) return true;
    const unsigned char* type = &file[at + 4];
    const bool critical = (type[0] & 0x20) == 0;  // an upper-case first letter: IHDR, IDAT, ...
    if (critical && crc32(crc32(0L, Z_NULL, 0), type, 4 + length) != bigEndian32(type + 4 + length)) {
      return true;
    }
    const std::string name(type, type + 4);
    const unsigned char* data = type + 4;
    if (at == 8) {
      if (name != "IHDR" || length != 13) return true;
      const std::uint32_t width = bigEndian32(data), height = bigEndian32(data + 4);
      if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide) return true;
      // Beyond OpenCV's limits imread refuses it anyway; not inflated (a few MB could take
      // seconds) to find out.
      if (!withinImageLimits(width, height)) return true;
      const unsigned bits = bitsPerPixel(data[9], data[8]);
      if (bits == 0) return true;
      expected = inflatedSize(width, height, bits, data[12] == 1);
    }
    if (name == "IDAT") image_data.emplace_back(data, length);
    if (name == "IEND") return !inflatesTo(image_data, expected);
    at += 12 + length;
  }
}

// Whether `bytes` start as one of the formats isImageFile() names does: PNG, JPEG, BMP, TIFF,
// PPM/PGM (and PBM), WebP. OpenCV picks its decoder by the bytes, not the name, and would hand
// anything else to whichever decoder claims it: its DICOM reader, for a file with "DICM" at byte
// 128, aborted the process on an assertion of GDCM's (found by fuzz/readers_fuzz).
bool hasImageSignature(const std::vector<uchar>& bytes) {
  const auto starts = [&bytes](std::initializer_list<uchar> head, size_t at = 0) {
    return bytes.size() >= at + head.size() &&
           std::equal(head.begin(), head.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at));
  };
  const bool netpbm = bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' &&
                      bytes[1] <= '6' && std::isspace(bytes[2]) != 0;
  return isPng(bytes) || isJpeg(bytes) || starts({'B', 'M'}) || starts({'I', 'I', 42, 0}) ||
         starts({'M', 'M', 0, 42}) || netpbm ||
         (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8));
}

// decodeImage's work on a regular file: its signature read first (a large file that is no
// image is not read whole), then the rest.
cv::Mat decodeFile(const std::string& path, int flags) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = file ? static_cast<std::streamoff>(file.tellg()) : 0;
  constexpr std::streamoff kHead = 16;
  std::vector<uchar> bytes(static_cast<size_t>(std::min(std::max<std::streamoff>(size, 0), kHead)));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!file || !hasImageSignature(bytes)) return cv::Mat();
  const size_t head = bytes.size();
  bytes.resize(static_cast<size_t>(size));
  file.read(reinterpret_cast<char*>(bytes.data() + head),
            static_cast<std::streamsize>(bytes.size() - head));
  if (!file) return cv::Mat();
  if (isJpeg(bytes)) {
    // A frame (read unchanged) is decoded here; any other use is checked here and decoded below.
    JpegRead jpeg = readJpeg(bytes, flags == cv::IMREAD_UNCHANGED);
    if (jpeg.damaged) return cv::Mat();
    if (!jpeg.image.empty()) return jpeg.image;
  }
  if (isPng(bytes) && flags == cv::IMREAD_UNCHANGED) {  // a frame: decoded here when it can be
    PngRead png = readPng(bytes);
    if (png.damaged) return cv::Mat();
    if (!png.image.empty()) return png.image;
  }
  if (isDamagedPng(bytes)) return cv::Mat();
  return cv::imdecode(bytes, flags);
}

}  // namespace

cv::Mat decodeImage(const std::string& path, int flags) {
  // Only a regular file: a FIFO or a device would block the read, or never end.
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return cv::Mat();
  try {
    return decodeFile(path, flags);
  } catch (const cv::Exception&) {  // a size within the limits that could not be allocated, ...
    return cv::Mat();
  } catch (const std::bad_alloc&) {
    return cv::Mat();
  }
}

std::string inputPath(const std::string& input) {
  std::error_code error;
  if (fs::is_directory(input, error)) return imageFolder(input);
  if (fs::exists(input, error)) return input;
  FramePattern pattern;
  if (parsePattern(input, &pattern)) return fs::path(input).parent_path().string();
  return "";
}

std::unique_ptr<FrameSource> FrameSource::open(const std::string& input, const DecoderLimits& limits) {
  if (input.empty()) throw std::runtime_error("the input path is empty");
  std::error_code error;
  if (fs::is_directory(input, error)) return std::make_unique<ImageListSource>(folderImages(input));
  FramePattern pattern;
  if (fs::exists(input, error) || isUrl(input)) {
    if (isImageFile(input)) throw std::runtime_error("'" + input + "' is a single image, not a video");
    try {
      return std::make_unique<VideoSource>(input, limits);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("cannot open video '" + input + "': " + e.what());
    }
  }
  if (parsePattern(input, &pattern)) {
    std::vector<std::string> files = patternFiles(pattern);
    if (files.empty()) throw std::runtime_error("no image matches the pattern '" + input + "'");
    return std::make_unique<ImageListSource>(std::move(files));
  }
  if (isCameraIndex(input)) return std::make_unique<CameraSource>(std::stoi(input));
  throw std::runtime_error("cannot open '" + input + "': no such file or folder");
}

}  // namespace movseg
