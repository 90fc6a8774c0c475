#include "motion/motion_fixture.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "test_support.h"

namespace movseg::test {

FramePair makePair(const PairSpec& spec) {
  const cv::Size canvas_size(spec.size.width * 2, spec.size.height * 2);
  const cv::Mat canvas = texture(canvas_size, spec.seed);
  const cv::Matx33d to_frame(1, 0, -spec.size.width / 2.0, 0, 1, -spec.size.height / 2.0, 0, 0, 1);
  FramePair pair;
  cv::warpAffine(canvas, pair.prev, cv::Mat(to_frame).rowRange(0, 2), spec.size);
  cv::warpPerspective(canvas, pair.cur, cv::Mat(spec.camera * to_frame), spec.size);
  pair.cur_mask = cv::Mat::zeros(spec.size, CV_8U);

  if (spec.object_fraction > 0) {
    // A textured ellipse of the requested area, moving by object_motion in the image.
    const double area = spec.object_fraction * spec.size.area();
    const cv::Size axes(static_cast<int>(std::sqrt(area / CV_PI * 1.5)),
                        static_cast<int>(std::sqrt(area / CV_PI / 1.5)));
    const cv::Mat object_texture = texture(spec.size, spec.seed + 1000);
    const cv::Point2d centre(spec.size.width * 0.45, spec.size.height * 0.5);
    for (int which = 0; which < 2; ++which) {
      const cv::Point2d at = which == 0 ? centre : centre + spec.object_motion;
      cv::Mat mask = cv::Mat::zeros(spec.size, CV_8U);
      cv::ellipse(mask, cv::Point(cvRound(at.x), cvRound(at.y)), axes, 0, 0, 360, 255, cv::FILLED);
      const cv::Matx23d shift(1, 0, at.x - centre.x, 0, 1, at.y - centre.y);
      cv::Mat moved;
      cv::warpAffine(object_texture, moved, shift, spec.size);
      moved.copyTo(which == 0 ? pair.prev : pair.cur, mask);
      if (which == 1) pair.cur_mask = mask;
    }
  }
  cv::RNG rng(spec.seed + 7);
  for (cv::Mat* frame : {&pair.prev, &pair.cur}) {
    cv::Mat noise(spec.size, CV_16SC3);
    rng.fill(noise, cv::RNG::NORMAL, 0, spec.noise_sigma);
    cv::Mat noisy;
    frame->convertTo(noisy, CV_16SC3);
    noisy += noise;
    noisy.convertTo(*frame, CV_8UC3);
  }
  return pair;
}

cv::Matx33d similarityAboutCentre(cv::Size size, double degrees, double scale, cv::Point2d shift,
                                  double shear) {
  const cv::Point2d c(size.width / 2.0, size.height / 2.0);
  const double a = degrees * CV_PI / 180.0;
  const cv::Matx33d to_centre(1, 0, -c.x, 0, 1, -c.y, 0, 0, 1);
  const cv::Matx33d back(1, 0, c.x + shift.x, 0, 1, c.y + shift.y, 0, 0, 1);
  const cv::Matx33d linear(scale * std::cos(a), -scale * std::sin(a) + shear, 0,
                           scale * std::sin(a), scale * std::cos(a), 0, 0, 0, 1);
  return back * linear * to_centre;
}

}  // namespace movseg::test
