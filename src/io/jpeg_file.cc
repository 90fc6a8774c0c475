#include "io/jpeg_file.h"

#include <csetjmp>
#include <cstdio>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <jerror.h>  // the message codes

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

// Warnings (level -1) of damaged data; not those of data that decodes whole, such as a few
// extraneous bytes before a marker, which some encoders write, or an unknown JFIF revision.
void onMessage(j_common_ptr info, int level) {
  if (level >= 0) return;  // trace messages
  switch (info->err->msg_code) {
    case JWRN_HIT_MARKER:     // premature end of a data segment
    case JWRN_HUFF_BAD_CODE:  // a bad Huffman code
    case JWRN_JPEG_EOF:       // the file ends before its end-of-image marker
    case JWRN_MUST_RESYNC:    // a restart marker missing
      reinterpret_cast<ErrorManager*>(info->err)->damaged = true;
      break;
    default:
      break;
  }
}

// The decompression, destroyed however the read ends (the longjmp skips no destructor of ours:
// everything that owns memory lives outside the setjmp's frame).
struct Decompress {
  jpeg_decompress_struct info{};
  ErrorManager errors;
  Decompress() {
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = onError;
    errors.manager.emit_message = onMessage;
    jpeg_create_decompress(&info);
  }
  ~Decompress() { jpeg_destroy_decompress(&info); }
  Decompress(const Decompress&) = delete;
  Decompress& operator=(const Decompress&) = delete;
};

// The steps that may longjmp back: nothing here has a destructor to skip but `image`, whose
// buffer is made before the first row is read and released by the caller.
bool read(Decompress* d, const std::vector<uchar>& bytes, bool decode, cv::Mat* image) {
  jpeg_decompress_struct& info = d->info;
  if (setjmp(d->errors.back) != 0) return false;
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  const bool grey = info.num_components == 1;
  if (!decode || (!grey && info.jpeg_color_space != JCS_YCbCr && info.jpeg_color_space != JCS_RGB)) {
    jpeg_read_coefficients(&info);
  } else {
    info.out_color_space = grey ? JCS_GRAYSCALE : JCS_EXT_BGR;
    jpeg_start_decompress(&info);
    image->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width),
                  grey ? CV_8UC1 : CV_8UC3);
    while (info.output_scanline < info.output_height) {
      JSAMPROW row = image->ptr(static_cast<int>(info.output_scanline));
      jpeg_read_scanlines(&info, &row, 1);
    }
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
