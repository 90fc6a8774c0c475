#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

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
// down only, and the bottom-right pixel is never on it. 255 = boundary. Whole shifted views at a
// time: a branch per pixel cost nearly a tenth of a DAVIS bench.
cv::Mat boundaryMap(const cv::Mat& mask) {
  const cv::Mat binary = mask != 0;
  cv::Mat boundary = cv::Mat::zeros(mask.size(), CV_8U);
  const int w = mask.cols, h = mask.rows;
  // The pixels of (x, y) and of its neighbour (x + dx, y + dy), for every x, y where both exist.
  const auto differs = [&](int dx, int dy) {
    const cv::Mat at = binary(cv::Rect(0, 0, w - dx, h - dy));
    const cv::Mat neighbour = binary(cv::Rect(dx, dy, w - dx, h - dy));
    cv::Mat out = boundary(cv::Rect(0, 0, w - dx, h - dy));
    cv::Mat step;
    cv::bitwise_xor(at, neighbour, step);
    cv::bitwise_or(out, step, out);
  };
  if (w > 1) differs(1, 0);
  if (h > 1) differs(0, 1);
  if (w > 1 && h > 1) differs(1, 1);
  return boundary;
}

// The half-widths of the rows of skimage.morphology.disk(radius), DAVIS's structuring element:
// row dy (-radius..radius, at dy + radius) spans -w..w, the largest w with w² + dy² <= radius².
std::vector<int> diskRows(int radius) {
  std::vector<int> half_widths;
  for (int dy = -radius; dy <= radius; ++dy) {
    int w = 0;
    while ((w + 1) * (w + 1) + dy * dy <= radius * radius) ++w;
    half_widths.push_back(w);
  }
  return half_widths;
}

// Running counts along each row of a boundary map: at (y, x), its pixels of row y left of x
// (CV_32S, a column more than the map).
cv::Mat rowCounts(const cv::Mat& boundary) {
  cv::Mat counts(boundary.rows, boundary.cols + 1, CV_32S);
  for (int y = 0; y < boundary.rows; ++y) {
    const uchar* in = boundary.ptr(y);
    int* out = counts.ptr<int>(y);
    out[0] = 0;
    for (int x = 0; x < boundary.cols; ++x) out[x + 1] = out[x] + (in[x] != 0);
  }
  return counts;
}

// countNonZero(from & dilate(to, disk)) for boundary maps: each of `from`'s pixels looks along
// the disk's rows for one of `to`'s (given by its rowCounts), and only its own pixels look.
// Dilating both maps of every frame whole was a sixth of a DAVIS bench's time at 320x240.
long countNear(const cv::Mat& from, const cv::Mat& to_counts, const std::vector<int>& disk) {
  const int radius = static_cast<int>(disk.size() / 2);
  const int width = from.cols;
  long near = 0;
  for (int y = 0; y < from.rows; ++y) {
    const uchar* row = from.ptr(y);
    for (int x = 0; x < width; ++x) {
      if (row[x] == 0) continue;
      for (int dy = std::max(-radius, -y); dy <= std::min(radius, from.rows - 1 - y); ++dy) {
        const int w = disk[dy + radius];
        const int* counts = to_counts.ptr<int>(y + dy);
        if (counts[std::min(x + w + 1, width)] > counts[std::max(x - w, 0)]) {
          ++near;
          break;
        }
      }
    }
  }
  return near;
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
  const std::vector<int> disk = diskRows(boundaryTolerance(pred.size()));
  return precisionRecall(countNear(pred_boundary, rowCounts(gt_boundary), disk),
                         cv::countNonZero(pred_boundary),
                         countNear(gt_boundary, rowCounts(pred_boundary), disk),
                         cv::countNonZero(gt_boundary))
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
