// Scores of predicted masks against ground truth: DAVIS's region similarity J and contour
// accuracy F, the paper's error rate (eq. 12) and CDnet's precision / recall / F1. Definitions,
// references and conventions: docs/metrics.md.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Precision, recall and their harmonic mean of a detection, with the empty-set conventions of
// DAVIS's f_measure: nothing predicted -> precision 1; nothing to find -> recall 1; so both empty
// scores 1 and exactly one empty scores 0.
struct PrecisionRecall {
  double precision = 1;
  double recall = 1;
  double f() const;  // 0 when precision + recall = 0
};

// `predicted_hits` of the `predicted` items are right; `truth_hits` of the `truth` items are found.
PrecisionRecall precisionRecall(long predicted_hits, long predicted, long truth_hits, long truth);

struct FrameScore {
  int frame = 0;          // frame number (see GtFrame::index)
  double j = 0;           // IoU of the foreground; 1 when both are empty
  double f = 0;           // boundaryF()
  double error_rate = 0;  // (fp + fn) / counted pixels, in percent; 0 when nothing is counted
  long tp = 0, fp = 0, fn = 0, tn = 0;  // foreground pixel counts, ignored pixels left out
  // Of the foreground pixels of this frame alone (PrecisionRecall's conventions).
  double precision() const;
  double recall() const;
  double f1() const;
};

// pred, gt: CV_8U, same size, non-zero = foreground. ignore: empty or CV_8U of the same size,
// non-zero = not counted by any score (F: cleared from both masks first, as DAVIS does with its
// void pixels). Throws std::invalid_argument when the sizes or types differ.
FrameScore scoreFrame(const cv::Mat& pred, const cv::Mat& gt, const cv::Mat& ignore = cv::Mat());

// DAVIS's boundary tolerance in pixels for masks of `size`: ceil(0.008 * diagonal).
int boundaryTolerance(cv::Size size);

// DAVIS's contour accuracy F (f_measure): the F-measure of the masks' one-pixel boundaries
// (seg2bmap), a boundary pixel being matched when the other boundary lies within
// boundaryTolerance() pixels (disk dilation). Both boundaries empty -> 1; one empty -> 0.
double boundaryF(const cv::Mat& pred, const cv::Mat& gt);

// The scores of one sequence. `frames` holds every scored frame, the first frame of the video
// included; every mean below leaves that frame out (it has no previous frame, so no motion cue)
// and is NaN when no other frame was scored.
struct SequenceScore {
  std::string name;
  std::vector<FrameScore> frames;    // by frame number
  int first_frame = 0;               // the video's first frame number: not counted
  int skipped = 0;                   // frames of the video without a ground-truth mask
  int missing = 0;                   // ground-truth frames (but the first) without a prediction
  bool matched_by_position = false;  // see scoreSequence()

  std::vector<FrameScore> counted() const;  // `frames` without the first frame
  double meanJ() const;
  double meanF() const;
  double meanErrorRate() const;
  double recallJ() const;  // share of counted frames with J > 0.5
  // Of the pixel counts summed over the counted frames (CDnet computes a video's figures so).
  double precision() const;
  double recall() const;
  double f1() const;
};

// One line of a score table: a sequence's figures, or their mean over sequences.
struct ScoreSummary {
  std::string name;
  int frames = 0;  // counted frames
  int skipped = 0;
  int missing = 0;
  double j = 0, j_recall = 0, f = 0, error_rate = 0, precision = 0, recall = 0, f1 = 0;
};

ScoreSummary summarize(const SequenceScore& score);

// Each figure averaged over the sequences (each sequence weighs the same, as in DAVIS and
// CDnet); frame counts are summed. NaN figures propagate.
ScoreSummary meanOverSequences(const std::vector<ScoreSummary>& rows, const std::string& name);

}  // namespace movseg
