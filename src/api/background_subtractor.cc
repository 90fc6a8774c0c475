#include "movseg/background_subtractor.h"

#include "movseg/segmenter.h"

namespace movseg {
namespace {

class MovingCameraSubtractor : public cv::BackgroundSubtractor {
 public:
  MovingCameraSubtractor(const Params& params, const cv::Mat& ignored_region)
      : segmenter_(params) {
    segmenter_.setIgnoredRegion(ignored_region);
  }

  void apply(cv::InputArray image, cv::OutputArray fgmask, double /*learningRate*/) override {
    segmenter_.process(image.getMat()).mask.copyTo(fgmask);
  }

  // The overload newer OpenCV releases declare pure virtual (a known foreground mask to learn
  // from). No `override`: OpenCV 4.6 does not declare it. There is no model to teach, so the
  // known mask is ignored.
  void apply(cv::InputArray image, cv::InputArray /*knownForegroundMask*/, cv::OutputArray fgmask,
             double learningRate) {
    apply(image, fgmask, learningRate);
  }

  void getBackgroundImage(cv::OutputArray backgroundImage) const override {
    segmenter_.compensatedPreviousFrame().copyTo(backgroundImage);
  }

  // cv::Algorithm::clear(): forget the stream, so the next frame is a first frame.
  void clear() override { segmenter_.reset(); }

  cv::String getDefaultName() const override { return "movseg.MovingCameraSubtractor"; }

 private:
  Segmenter segmenter_;
};

}  // namespace

cv::Ptr<cv::BackgroundSubtractor> createMovingCameraSubtractor(const Params& params,
                                                               const cv::Mat& ignored_region) {
  return cv::makePtr<MovingCameraSubtractor>(params, ignored_region);
}

}  // namespace movseg
