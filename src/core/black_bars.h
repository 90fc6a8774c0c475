// Letterbox and pillarbox bars: rows and columns of flat black along a frame's border, around
// the picture itself. A video made for another aspect ratio carries them, and so do many
// stabilised, cropped or re-encoded ones.
#pragma once

#include <opencv2/core.hpp>

namespace movseg {

// The picture inside `bgr`'s black bars (8-bit BGR): the frame without the rows and columns, from
// each side inwards, whose pixels are black on average (their brightest channel at most 24 of
// 255 on average, as FFmpeg's cropdetect reads black) and nowhere brighter than 64 (a lamp in a
// dark sky is picture). The whole frame when no bar is found, or when bars would leave less than
// a quarter of a side: a dark frame is no bar.
cv::Rect pictureInsideBlackBars(const cv::Mat& bgr);

}  // namespace movseg
