// §3.1 correspondences: pyramid Lucas–Kanade forward and backward, filtered by ZNCC (eq. 2)
// and by the forward–backward distance, each against its median.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "movseg/params.h"

namespace movseg {

struct Track {
  cv::Point2f prev;        // f_i^t, where the feature was detected
  cv::Point2f cur;         // f_i^{t+1}, forward LK
  float zncc = 0;          // ZNCC(prev, cur), eq. (2)
  float fb_distance = 0;   // Dis(f_i^t, backward LK of cur)
};

// Tracks `points` of the previous frame into the current one and back. `predicted` maps
// previous to current coordinates (the warm start) and gives LK its initial guess. Tracks
// that LK loses either way are dropped.
std::vector<Track> trackForwardBackward(const std::vector<cv::Mat>& prev_pyramid,
                                        const std::vector<cv::Mat>& cur_pyramid,
                                        const std::vector<cv::Point2f>& points,
                                        const cv::Matx33d& predicted, const Params& params);

// Eq. (2) over a window x window patch centred on a (in image_a) and b (in image_b), sampled
// at sub-pixel positions. Flat patches score 0.
float zncc(const cv::Mat& image_a, cv::Point2f a, const cv::Mat& image_b, cv::Point2f b,
           int window);

// Keeps the tracks with ZNCC >= eta1 and forward–backward distance <= eta2, where eta1 and eta2
// are the medians over `tracks` (the paper's rule). The result is S_m.
std::vector<Track> filterTracks(const std::vector<Track>& tracks);

}  // namespace movseg
