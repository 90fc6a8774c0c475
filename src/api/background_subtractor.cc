#include "movseg/background_subtractor.h"

#include <mutex>

#include "movseg/segmenter.h"

namespace movseg {
namespace {

// Its calls are serialised: cv2 releases the GIL in apply(), so Python threads sharing one
// subtractor would otherwise corrupt the segmenter's state (MOG2's crash, not repeated here).
class MovingCameraSubtractor : public cv::BackgroundSubtractor {
 public:
  MovingCameraSubtractor(const Params& params, const cv::Mat& ignored_region)
      : segmenter_(params) {
    segmenter_.setIgnoredRegion(ignored_region);
  }

  void apply(cv::InputArray image, cv::OutputArray fgmask, double /*learningRate*/) override {
    const std::lock_guard<std::mutex> lock(mutex_);
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
    const std::lock_guard<std::mutex> lock(mutex_);
    segmenter_.compensatedPreviousFrame().copyTo(backgroundImage);
  }

  // cv::Algorithm::clear(): forget the stream, so the next frame is a first frame.
  void clear() override {
    const std::lock_guard<std::mutex> lock(mutex_);
    segmenter_.reset();
  }

  // The key cv::Algorithm::save() writes the state under: letters, digits, '_' and '-' only.
  cv::String getDefaultName() const override { return "movseg_MovingCameraSubtractor"; }

 private:
  mutable std::mutex mutex_;
  Segmenter segmenter_;
};

}  // namespace

cv::Ptr<cv::BackgroundSubtractor> createMovingCameraSubtractor(const Params& params,
                                                               const cv::Mat& ignored_region) {
  return cv::makePtr<MovingCameraSubtractor>(params, ignored_region);
}

}  // namespace movseg
