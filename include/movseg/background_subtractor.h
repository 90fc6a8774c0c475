// movseg behind OpenCV's cv::BackgroundSubtractor interface, so code written for
// cv::createBackgroundSubtractorMOG2() switches to a moving camera by changing one line.
#pragma once

#include <opencv2/video/background_segm.hpp>

#include "movseg/params.h"

namespace movseg {

// apply(frame, fgmask, learningRate) runs Segmenter::process(frame) and writes its 0 / 255 mask
// to fgmask; learningRate is ignored, because every mask comes from the last two frames only
// (there is no background model to learn). getBackgroundImage() gives
// Segmenter::compensatedPreviousFrame(). Throws std::invalid_argument when params.check() fails.
cv::Ptr<cv::BackgroundSubtractor> createMovingCameraSubtractor(const Params& params = Params());

}  // namespace movseg
