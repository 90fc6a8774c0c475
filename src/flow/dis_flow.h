// Dense Inverse Search optical flow (Kroeger et al. 2016) as OpenCV's cv::DISOpticalFlow computes
// it with movseg's settings: the FAST preset (8x8 patches every 4 pixels, 16 gradient-descent
// iterations over two passes, mean-normalised patches, spatial propagation), the finest scale
// given, no variational refinement. It follows OpenCV 4.6's float arithmetic operation for
// operation, so that its flow is OpenCV's: identical on every pair tried
// (tests/flow/dis_flow_test.cc). It is faster because it does less work for the same numbers:
// - a frame is prepared once (pyramid, gradients, structure tensors) and serves as the first
//   image of one pair and the second of the next, where OpenCV rebuilds both pyramids per pair;
// - the images are kept as floats, so that a patch's row is two loads where OpenCV widens bytes
//   and shorts on every visit of a patch;
// - a candidate's differences are kept, so that the descent's first step, at the best candidate,
//   is not computed again, and the initial flow's candidate, tried at a patch in both passes, is
//   matched once;
// - densification works on four pixels at once (OpenCV's is scalar), and so does the scaling up
//   of the finest level's flow along x (cv::resize's is scalar there);
// - the initial flow and the coarser level's flow are read at the patches' centres alone,
//   where OpenCV resizes whole fields and reads those centres.
// Buffers are kept across calls: a stream of frames of one size allocates nothing once started.
// One object per stream: calc() uses the object's buffers.
#pragma once

#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/video/tracking.hpp>

namespace movseg {

// How cv::resize (INTER_LINEAR) weighs its source along one axis for one destination index: two
// source indices and their weights. DisFlow scales flows as OpenCV's DIS does, with its
// arithmetic.
struct ResizeTaps {
  int first, second;
  float w_first, w_second;
};

// One frame as DIS reads it, at every level of its pyramid from the finest scale to the
// coarsest. Made by DisFlow::prepare.
class DisFrame {
 public:
  cv::Size size() const { return size_; }
  bool empty() const { return levels_.empty(); }

  // What the patch search knows of a patch of the first image: its gradients summed, and the
  // inverse of its structure tensor, the Gauss-Newton step's matrix.
  struct PatchGradients {
    float inv_xx, inv_xy, inv_yy;
    float sum_x, sum_y;
  };

 private:
  friend class DisFlow;

  struct Level {
    cv::Size size;
    cv::Mat grey;            // CV_8U: the finer level halved by area averaging
    cv::Mat grey_bordered;   // CV_8U: grey with kBorder pixels replicated on every side
    cv::Mat image;           // CV_32F: grey_bordered, where patches are matched
    cv::Mat grad_x, grad_y;  // CV_32F: 3x3 Sobel of grey (cv::spatialGradient, reflected border)
    cv::Mat grad_x16, grad_y16;  // CV_16S: spatialGradient's output
    std::vector<PatchGradients> patches;  // row by row, every kPatchStride pixels
    const float* pixels() const;          // grey's first pixel in `image`
  };

  cv::Size size_;
  int finest_scale_ = 0;
  std::vector<Level> levels_;  // [0] at finest_scale_
};

class DisFlow {
 public:
  // `finest_scale`: the pyramid level the search stops at (0 = full resolution, 1 = half, ...);
  // the flow there is scaled up to the frame's size.
  explicit DisFlow(int finest_scale);

  // Prepares `grey` (CV_8U, continuous, at least 16 pixels a side) into *frame, reusing its
  // buffers.
  void prepare(const cv::Mat& grey, DisFrame* frame);

  // The flow from `from` to `to` (prepared by this object, of one size) into *flow (CV_32FC2):
  // from(p) matches to(p + flow(p)), as cv::DISOpticalFlow::calc(from, to, flow). `initial`,
  // when not empty (CV_32FC2 of the frames' size; it may be *flow itself), is tried at every
  // patch as OpenCV tries the flow it is given (a warm start).
  void calc(const DisFrame& from, const DisFrame& to, const cv::Mat& initial, cv::Mat* flow);

  // How far from a pixel, in the frame's pixels, the image shapes its flow: the side of a patch
  // at the finest scale, any of which covering the pixel has a say in its flow.
  int reach() const;

 private:
  struct LevelShape;

  void prepareLevel(const cv::Mat& grey, DisFrame::Level* level);
  void sampleInitialFlow(const cv::Mat& initial, const LevelShape& shape, int scale);
  void sampleCoarserFlow(const LevelShape& shape);
  void searchPatches(const DisFrame::Level& from, const DisFrame::Level& to,
                     const LevelShape& shape, bool warm);
  void densify(const DisFrame::Level& from, const DisFrame::Level& to, const LevelShape& shape,
               float scale, cv::Mat* dense);
  void upsample(const cv::Mat& dense, cv::Mat* flow);

  int finest_scale_;
  // Per patch of the current level: the flow searched (sparse), the flow it starts from (the
  // coarser level's, scaled up), the initial flow's candidate and its SSD.
  std::vector<float> sparse_x_, sparse_y_, start_x_, start_y_, initial_x_, initial_y_;
  std::vector<float> initial_ssd_;
  cv::Mat dense_;        // CV_32FC2: the last level's dense flow
  cv::Mat dense_level_;  // the view of dense_ at the current level's size
  std::vector<float> blocks_, row_sums_, totals_, running_;  // the structure tensors' sums
  std::vector<float> resampled_rows_[2];                     // upsample's rows along x
  std::vector<ResizeTaps> x_taps_;
};

// OpenCV's DIS with the settings DisFlow follows: the reference it is measured against.
cv::Ptr<cv::DISOpticalFlow> openCvDis(int finest_scale);

}  // namespace movseg
