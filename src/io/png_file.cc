#include "io/png_file.h"

#include <algorithm>
#include <csetjmp>
#include <cstring>

#include <png.h>

#include "io/image_limits.h"

namespace movseg {
namespace {

struct Source {
  const std::vector<uchar>* bytes;
  size_t at;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* source = static_cast<Source*>(png_get_io_ptr(png));
  if (length > source->bytes->size() - source->at) png_error(png, "read past the end");
  std::memcpy(out, source->bytes->data() + source->at, length);
  source->at += length;
}

[[noreturn]] void onError(png_structp png, png_const_charp /*message*/) {
  png_longjmp(png, 1);
}

void onWarning(png_structp /*png*/, png_const_charp /*message*/) {}  // an ancillary chunk's CRC, ...

// libpng's read and info structures, destroyed however the read ends.
struct Decompress {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, onError, onWarning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  png_infop end = png != nullptr ? png_create_info_struct(png) : nullptr;
  ~Decompress() { png_destroy_read_struct(&png, &info, &end); }
  Decompress() = default;
  Decompress(const Decompress&) = delete;
  Decompress& operator=(const Decompress&) = delete;
};

// The steps that may longjmp back: no object with a destructor lives in this frame, and
// `image` is the caller's.
bool read(const Decompress& d, cv::Mat* image) {
  png_structp png = d.png;
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_read_info(png, d.info);
  png_uint_32 width = 0, height = 0;
  int depth = 0, colour = 0, interlace = 0;
  png_get_IHDR(png, d.info, &width, &height, &depth, &colour, &interlace, nullptr, nullptr);
  if (!withinImageLimits(width, height)) return false;
  const bool grey = colour == PNG_COLOR_TYPE_GRAY, rgb = colour == PNG_COLOR_TYPE_RGB;
  if (depth != 8 || (!grey && !rgb) || interlace != PNG_INTERLACE_NONE ||
      png_get_valid(png, d.info, PNG_INFO_tRNS) != 0) {
    return true;  // not a format read here: `image` stays empty
  }
  if (rgb) png_set_bgr(png);
  png_read_update_info(png, d.info);
  image->create(static_cast<int>(height), static_cast<int>(width), grey ? CV_8UC1 : CV_8UC3);
  for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, image->ptr(static_cast<int>(y)), nullptr);
  png_read_end(png, d.end);
  return true;
}

}  // namespace

bool isPng(const std::vector<uchar>& bytes) {
  static constexpr uchar kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  return bytes.size() >= 8 && std::equal(kSignature, kSignature + 8, bytes.begin());
}

PngRead readPng(const std::vector<uchar>& bytes) {
  PngRead result;
  const Decompress d;
  if (d.info == nullptr || d.end == nullptr) return result;
  Source source{&bytes, 0};
  png_set_read_fn(d.png, &source, readFromMemory);
  result.damaged = !read(d, &result.image);
  if (result.damaged) result.image.release();
  return result;
}

}  // namespace movseg
