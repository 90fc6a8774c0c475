#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace movseg {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// DAVIS's bound_th: the boundary tolerance as a fraction of the image diagonal.
constexpr double kBoundaryFraction = 0.008;

// J counts as recalled above this IoU (DAVIS's recall).
constexpr double kRecallThreshold = 0.5;

void checkMaskPair(const cv::Mat& a, const cv::Mat& b, const char* function) {
  if (a.size() != b.size() || a.type() != CV_8UC1 || b.type() != CV_8UC1) {
    throw std::invalid_argument(std::string(function) + ": masks must be CV_8UC1 of one size");
  }
}

// DAVIS's seg2bmap (after D. Martin's BSDS code): a pixel is on the boundary when it differs
// from its right, lower or lower-right neighbour; the last row looks right only, the last column
// down only, and the bottom-right pixel is never on it. 255 = boundary.
cv::Mat boundaryMap(const cv::Mat& mask) {
  cv::Mat boundary(mask.size(), CV_8U);
  const int last_row = mask.rows - 1;
  const int last_col = mask.cols - 1;
  for (int y = 0; y < mask.rows; ++y) {
    const uchar* row = mask.ptr(y);
    const uchar* below = mask.ptr(std::min(y + 1, last_row));
    uchar* out = boundary.ptr(y);
    for (int x = 0; x < mask.cols; ++x) {
      const bool value = row[x] != 0;
      const bool right = x < last_col && (row[x + 1] != 0) != value;
      const bool down = y < last_row && (below[x] != 0) != value;
      const bool diagonal = y < last_row && x < last_col && (below[x + 1] != 0) != value;
      const bool on = y == last_row ? right : x == last_col ? down : right || down || diagonal;
      out[x] = on ? 255 : 0;
    }
  }
  return boundary;
}

// skimage.morphology.disk(radius), the structuring element of DAVIS's dilation.
cv::Mat disk(int radius) {
  cv::Mat kernel(2 * radius + 1, 2 * radius + 1, CV_8U);
  for (int y = -radius; y <= radius; ++y) {
    for (int x = -radius; x <= radius; ++x) {
      kernel.at<uchar>(y + radius, x + radius) = x * x + y * y <= radius * radius ? 1 : 0;
    }
  }
  return kernel;
}

PrecisionRecall pixelScores(const FrameScore& counts) {
  return precisionRecall(counts.tp, counts.tp + counts.fp, counts.tp, counts.tp + counts.fn);
}

// The counted frames' pixel counts, summed.
FrameScore totals(const std::vector<FrameScore>& frames) {
  FrameScore sum;
  for (const FrameScore& frame : frames) {
    sum.tp += frame.tp;
    sum.fp += frame.fp;
    sum.fn += frame.fn;
    sum.tn += frame.tn;
  }
  return sum;
}

// A pixel figure of the frames' summed counts; NaN without frames.
double ofTotals(const std::vector<FrameScore>& frames, double (FrameScore::*figure)() const) {
  return frames.empty() ? kNaN : (totals(frames).*figure)();
}

template <typename Value>
double mean(const std::vector<FrameScore>& frames, Value value) {
  if (frames.empty()) return kNaN;
  double sum = 0;
  for (const FrameScore& frame : frames) sum += value(frame);
  return sum / static_cast<double>(frames.size());
}

template <typename Field>
double meanOf(const std::vector<ScoreSummary>& rows, Field field) {
  double sum = 0;
  for (const ScoreSummary& row : rows) sum += row.*field;
  return rows.empty() ? kNaN : sum / static_cast<double>(rows.size());
}

}  // namespace

double PrecisionRecall::f() const {
  return precision + recall == 0 ? 0 : 2 * precision * recall / (precision + recall);
}

PrecisionRecall precisionRecall(long predicted_hits, long predicted, long truth_hits, long truth) {
  PrecisionRecall result;
  if (predicted > 0) result.precision = static_cast<double>(predicted_hits) / predicted;
  if (truth > 0) result.recall = static_cast<double>(truth_hits) / truth;
  return result;
}

double FrameScore::precision() const { return pixelScores(*this).precision; }
double FrameScore::recall() const { return pixelScores(*this).recall; }
double FrameScore::f1() const { return pixelScores(*this).f(); }

FrameScore scoreFrame(const cv::Mat& pred, const cv::Mat& gt, const cv::Mat& ignore) {
  checkMaskPair(pred, gt, "scoreFrame");
  cv::Mat counted(pred.size(), CV_8U, cv::Scalar(255));
  if (!ignore.empty()) {
    checkMaskPair(pred, ignore, "scoreFrame");
    counted = ignore == 0;
  }
  const cv::Mat predicted = (pred != 0) & counted;
  const cv::Mat truth = (gt != 0) & counted;
  FrameScore score;
  score.tp = cv::countNonZero(predicted & truth);
  score.fp = cv::countNonZero(predicted) - score.tp;
  score.fn = cv::countNonZero(truth) - score.tp;
  const long pixels = cv::countNonZero(counted);
  score.tn = pixels - score.tp - score.fp - score.fn;
  const long union_size = score.tp + score.fp + score.fn;
  score.j = union_size == 0 ? 1 : static_cast<double>(score.tp) / union_size;
  score.error_rate = pixels == 0 ? 0 : 100.0 * (score.fp + score.fn) / pixels;
  score.f = boundaryF(predicted, truth);
  return score;
}

int boundaryTolerance(cv::Size size) {
  return static_cast<int>(std::ceil(kBoundaryFraction * std::hypot(size.width, size.height)));
}

double boundaryF(const cv::Mat& pred, const cv::Mat& gt) {
  checkMaskPair(pred, gt, "boundaryF");
  const cv::Mat pred_boundary = boundaryMap(pred);
  const cv::Mat gt_boundary = boundaryMap(gt);
  const cv::Mat kernel = disk(boundaryTolerance(pred.size()));
  cv::Mat pred_near, gt_near;
  cv::dilate(pred_boundary, pred_near, kernel);
  cv::dilate(gt_boundary, gt_near, kernel);
  return precisionRecall(cv::countNonZero(pred_boundary & gt_near), cv::countNonZero(pred_boundary),
                         cv::countNonZero(gt_boundary & pred_near), cv::countNonZero(gt_boundary))
      .f();
}

std::vector<FrameScore> SequenceScore::counted() const {
  std::vector<FrameScore> result;
  std::copy_if(frames.begin(), frames.end(), std::back_inserter(result),
               [this](const FrameScore& frame) { return frame.frame != first_frame; });
  return result;
}

double SequenceScore::meanJ() const {
  return mean(counted(), [](const FrameScore& frame) { return frame.j; });
}

double SequenceScore::meanF() const {
  return mean(counted(), [](const FrameScore& frame) { return frame.f; });
}

double SequenceScore::meanErrorRate() const {
  return mean(counted(), [](const FrameScore& frame) { return frame.error_rate; });
}

double SequenceScore::recallJ() const {
  return mean(counted(),
              [](const FrameScore& frame) { return frame.j > kRecallThreshold ? 1.0 : 0.0; });
}

double SequenceScore::precision() const { return ofTotals(counted(), &FrameScore::precision); }
double SequenceScore::recall() const { return ofTotals(counted(), &FrameScore::recall); }
double SequenceScore::f1() const { return ofTotals(counted(), &FrameScore::f1); }

ScoreSummary summarize(const SequenceScore& score) {
  ScoreSummary row;
  row.name = score.name;
  row.frames = static_cast<int>(score.counted().size());
  row.skipped = score.skipped;
  row.missing = score.missing;
  row.j = score.meanJ();
  row.j_recall = score.recallJ();
  row.f = score.meanF();
  row.error_rate = score.meanErrorRate();
  row.precision = score.precision();
  row.recall = score.recall();
  row.f1 = score.f1();
  return row;
}

ScoreSummary meanOverSequences(const std::vector<ScoreSummary>& rows, const std::string& name) {
  ScoreSummary mean_row;
  mean_row.name = name;
  for (const ScoreSummary& row : rows) {
    mean_row.frames += row.frames;
    mean_row.skipped += row.skipped;
    mean_row.missing += row.missing;
  }
  mean_row.j = meanOf(rows, &ScoreSummary::j);
  mean_row.j_recall = meanOf(rows, &ScoreSummary::j_recall);
  mean_row.f = meanOf(rows, &ScoreSummary::f);
  mean_row.error_rate = meanOf(rows, &ScoreSummary::error_rate);
  mean_row.precision = meanOf(rows, &ScoreSummary::precision);
  mean_row.recall = meanOf(rows, &ScoreSummary::recall);
  mean_row.f1 = meanOf(rows, &ScoreSummary::f1);
  return mean_row;
}

}  // namespace movseg
