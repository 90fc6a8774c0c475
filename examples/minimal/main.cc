// Segments the moving objects of a video and writes one mask per frame, OUTDIR/00000.png, ...
// Usage: segment_video INPUT OUTDIR   (INPUT: video file, stream URL, or frames/%05d.png)
#include <cstdio>
#include <string>

#include <movseg/segmenter.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s INPUT OUTDIR\n", argv[0]);
    return 2;
  }
  cv::VideoCapture video(argv[1]);
  if (!video.isOpened()) {
    std::fprintf(stderr, "cannot open %s\n", argv[1]);
    return 1;
  }
  movseg::Params params;  // every field is documented in movseg/params.def
  params.static_camera = false;  // true for a fixed camera: no alignment
  movseg::Segmenter segmenter(params);
  for (int index = 0;; ++index) {
    cv::Mat frame;
    if (!video.read(frame)) break;
    const movseg::Result result = segmenter.process(frame);  // mask: CV_8U, 0 / 255
    char name[32];
    std::snprintf(name, sizeof name, "/%05d.png", index);
    if (!cv::imwrite(argv[2] + std::string(name), result.mask)) {
      std::fprintf(stderr, "cannot write %s%s\n", argv[2], name);
      return 1;
    }
    std::printf("frame %d: %d moving pixels\n", index, cv::countNonZero(result.mask));
  }
  return 0;
}
