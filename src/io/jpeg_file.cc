#include "io/jpeg_file.h"

#include <csetjmp>
#include <cstdio>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <jerror.h>  // the message codes

#include "io/image_limits.h"

#ifndef JCS_EXTENSIONS
#error "libjpeg-turbo is needed (JCS_EXT_BGR): Debian's libjpeg-dev is it"
#endif

namespace movseg {
namespace {

// libjpeg's error manager, with a way back from errors and a tally of the warnings that say the
// data is damaged. Messages are not printed.
struct ErrorManager {
  jpeg_error_mgr manager;
  std::jmp_buf back;
  bool damaged = false;
};

[[noreturn]] void onError(j_common_ptr info) {
  std::longjmp(reinterpret_cast<ErrorManager*>(info->err)->back, 1);
}

// Warnings (level -1) of damaged data; not those of data that decodes whole: a few extraneous
// bytes before the end-of-image marker, which some encoders write, or an unknown JFIF revision.
// (Extraneous bytes before any other marker are a segment cut short.)
bool damages(const jpeg_error_mgr& error) {
  switch (error.msg_code) {
    case JWRN_HIT_MARKER:         // premature end of a data segment
    case JWRN_HUFF_BAD_CODE:      // a bad Huffman code
    case JWRN_ARITH_BAD_CODE:     // a bad arithmetic code
    case JWRN_JPEG_EOF:           // the file ends before its end-of-image marker
    case JWRN_MUST_RESYNC:        // a restart marker missing
    case JWRN_NOT_SEQUENTIAL:     // invalid scan parameters
    case JWRN_BOGUS_PROGRESSION:  // an inconsistent progression
      return true;
    case JWRN_EXTRANEOUS_DATA:
      return error.msg_parm.i[1] != 0xD9 || error.msg_parm.i[0] > 16;
    default:
      return false;
  }
}

void onMessage(j_common_ptr info, int level) {
  if (level < 0 && damages(*info->err)) reinterpret_cast<ErrorManager*>(info->err)->damaged = true;
}

// The decompression object, destroyed however the read ends, when it was made.
struct Decompress {
  jpeg_decompress_struct info{};
  ErrorManager errors;
  bool made = false;
  Decompress() {
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = onError;
    errors.manager.emit_message = onMessage;
  }
  ~Decompress() {
    if (made) jpeg_destroy_decompress(&info);
  }
  Decompress(const Decompress&) = delete;
  Decompress& operator=(const Decompress&) = delete;
};

// The steps that may longjmp back (libjpeg's errors, from jpeg_create_decompress on): no
// object with a destructor lives in this frame, and `image` is the caller's.
bool read(Decompress* d, const std::vector<uchar>& bytes, bool decode, cv::Mat* image) {
  jpeg_decompress_struct& info = d->info;
  if (setjmp(d->errors.back) != 0) return false;
  jpeg_create_decompress(&info);
  d->made = true;
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  if (!withinImageLimits(info.image_width, info.image_height)) return false;
  const bool grey = info.num_components == 1;
  if (!decode || (!grey && info.jpeg_color_space != JCS_YCbCr && info.jpeg_color_space != JCS_RGB)) {
    jpeg_read_coefficients(&info);
  } else {
    info.out_color_space = grey ? JCS_GRAYSCALE : JCS_EXT_BGR;
    jpeg_start_decompress(&info);
    image->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width),
                  grey ? CV_8UC1 : CV_8UC3);
    // Row by row until the end, or until the data shows damage: the rest would be decoded from
    // nothing (a file cut short is padded with an end-of-image marker, row after row).
    while (info.output_scanline < info.output_height && !d->errors.damaged) {
      JSAMPROW row = image->ptr(static_cast<int>(info.output_scanline));
      jpeg_read_scanlines(&info, &row, 1);
    }
    if (d->errors.damaged) return false;
  }
  jpeg_finish_decompress(&info);
  return true;
}

}  // namespace

bool isJpeg(const std::vector<uchar>& bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

JpegRead readJpeg(const std::vector<uchar>& bytes, bool decode) {
  Decompress d;
  JpegRead result;
  const bool whole = read(&d, bytes, decode, &result.image);
  result.damaged = !whole || d.errors.damaged;
  if (result.damaged) result.image.release();
  return result;
}

}  // namespace movseg
