// movseg behind OpenCV's cv::BackgroundSubtractor interface, so code written for
// cv::createBackgroundSubtractorMOG2() switches to a moving camera by changing one line.
#pragma once

#include <opencv2/video/background_segm.hpp>

#include "movseg/params.h"

namespace movseg {

// apply(frame, fgmask, learningRate) runs Segmenter::process(frame) with the method of
// params.method and writes its 0 / 255 mask to fgmask; learningRate (and the known foreground
// mask of newer OpenCV's four-argument apply) is ignored: the methods keep their own memory.
// getBackgroundImage() gives Segmenter::compensatedPreviousFrame(); clear() forgets the stream,
// as Segmenter::reset() does. `ignored_region`: what is fixed to the camera, as
// Segmenter::setIgnoredRegion takes it (empty: none), for the subtractor's whole life. Throws
// std::invalid_argument when params.check() fails or the region is not CV_8U with one channel.
cv::Ptr<cv::BackgroundSubtractor> createMovingCameraSubtractor(
    const Params& params = Params(), const cv::Mat& ignored_region = cv::Mat());

}  // namespace movseg
