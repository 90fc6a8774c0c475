// A cv::BackgroundSubtractor loop, switched from MOG2 to movseg by one line.
// Usage: drop_in INPUT   (INPUT: video file, stream URL, or frames/%05d.png)
#include <cstdio>

#include <movseg/background_subtractor.h>
#include <opencv2/videoio.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s INPUT\n", argv[0]);
    return 2;
  }
  cv::VideoCapture video(argv[1]);
  // Was: cv::Ptr<cv::BackgroundSubtractor> subtractor = cv::createBackgroundSubtractorMOG2();
  cv::Ptr<cv::BackgroundSubtractor> subtractor = movseg::createMovingCameraSubtractor();
  for (int index = 0;; ++index) {
    cv::Mat frame, mask;
    if (!video.read(frame)) break;
    subtractor->apply(frame, mask);
    std::printf("frame %d: %d moving pixels\n", index, cv::countNonZero(mask));
  }
  return 0;
}
