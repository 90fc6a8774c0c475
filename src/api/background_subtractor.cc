#include "movseg/background_subtractor.h"

#include "movseg/segmenter.h"

namespace movseg {
namespace {

class MovingCameraSubtractor : public cv::BackgroundSubtractor {
 public:
  explicit MovingCameraSubtractor(const Params& params) : segmenter_(params) {}

  void apply(cv::InputArray image, cv::OutputArray fgmask, double /*learningRate*/) override {
    segmenter_.process(image.getMat()).mask.copyTo(fgmask);
  }

  void getBackgroundImage(cv::OutputArray backgroundImage) const override {
    segmenter_.compensatedPreviousFrame().copyTo(backgroundImage);
  }

 private:
  Segmenter segmenter_;
};

}  // namespace

cv::Ptr<cv::BackgroundSubtractor> createMovingCameraSubtractor(const Params& params) {
  return cv::makePtr<MovingCameraSubtractor>(params);
}

}  // namespace movseg
