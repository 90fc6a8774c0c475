// JPEG files read with libjpeg(-turbo) directly: the same library and settings OpenCV's imread
// uses (the same pixels, checked on every DAVIS frame), but with its warnings caught. libjpeg
// decodes a damaged file (a bad Huffman code, data cut short) with a warning on stderr and
// whatever the damage leaves in the rows, which a frame must not be; through cv::imread such a
// frame went by with a foreign line on stderr.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Whether `bytes` start as a JPEG file does (the start-of-image marker FF D8 FF).
bool isJpeg(const std::vector<uchar>& bytes);

struct JpegRead {
  bool damaged = false;  // an error, or a warning that the data is corrupt
  cv::Mat image;         // decoded when asked and it could be: BGR, or grey for a grey file
};

// Reads the JPEG file `bytes`. With `decode`, a grey or colour (YCbCr) file is decoded as
// cv::imread(..., IMREAD_UNCHANGED) decodes it; any other (CMYK) and any file without `decode`
// is only checked, by decoding its coefficients, and `image` stays empty. Nothing is printed.
JpegRead readJpeg(const std::vector<uchar>& bytes, bool decode);

}  // namespace movseg
