// `segment --show`: the overlay in a window, for camera demos.
#pragma once

#include <opencv2/core.hpp>

namespace movseg::cli {

// q, Esc or closing the window ends the run. Throws std::runtime_error at construction when
// enabled and no display answers.
class LiveWindow {
 public:
  explicit LiveWindow(bool enabled);
  ~LiveWindow();
  LiveWindow(const LiveWindow&) = delete;
  LiveWindow& operator=(const LiveWindow&) = delete;

  // False when the viewer asked to stop.
  bool show(const cv::Mat& picture);

 private:
  bool enabled_;
};

}  // namespace movseg::cli
