// Matching predicted masks to ground-truth frames and scoring them (declared in dataset.h).
#include "eval/dataset.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace movseg {
namespace {

// Whether `numbers` (in order) are 0, 1, 2, ... without a gap.
template <typename Numbers>
bool countsFromZero(const Numbers& numbers) {
  int expected = 0;
  for (const int number : numbers) {
    if (number != expected++) return false;
  }
  return true;
}

// `movseg segment` numbers its masks by position from 00000. Where the frames folder is not
// numbered so (CDnet's frames start at in000001; a subsampled sequence holds 00000, 00003, ...),
// a frame 0 that the video does not have gives that numbering away, and so do predictions
// numbered 0, 1, 2, ... without a gap: masks named by their frames' numbers would skip as the
// frames do.
bool numberedByPosition(const GtSequence& sequence, const std::map<int, std::string>& predictions) {
  const std::vector<int>& video = sequence.video_frames;
  if (predictions.count(0) == 0 || video.empty() || countsFromZero(video)) return false;
  std::vector<int> numbers;
  for (const auto& entry : predictions) numbers.push_back(entry.first);
  return std::find(video.begin(), video.end(), 0) == video.end() ||
         (numbers.size() > 1 && countsFromZero(numbers));
}

// Position of frame `index` in the frames folder; -1 when the folder does not hold it.
int positionOf(const GtSequence& sequence, int index) {
  const std::vector<int>& video = sequence.video_frames;
  const auto where = std::find(video.begin(), video.end(), index);
  return where == video.end() ? -1 : static_cast<int>(where - video.begin());
}

// Frames of the video (the frames folder, else the predictions) within the temporal ROI that
// have no ground-truth mask.
int countSkipped(const GtSequence& sequence, const std::map<int, std::string>& predictions) {
  std::vector<int> video = sequence.video_frames;
  if (video.empty()) {
    for (const auto& entry : predictions) video.push_back(entry.first);
  }
  std::set<int> annotated;
  for (const GtFrame& frame : sequence.frames) annotated.insert(frame.index);
  return static_cast<int>(std::count_if(video.begin(), video.end(), [&](int index) {
    return index >= sequence.roi_first && index <= sequence.roi_last && annotated.count(index) == 0;
  }));
}

std::string sizeText(const cv::Mat& image) {
  return std::to_string(image.cols) + "x" + std::to_string(image.rows);
}

FrameScore scoreFiles(const GtSequence& sequence, const GtFrame& frame,
                      const std::string& pred_path) {
  cv::Mat ignore;
  const cv::Mat truth = readGtMask(sequence, frame, &ignore);
  const cv::Mat pred = readMask(pred_path);
  if (pred.size() != truth.size()) {
    throw std::runtime_error("prediction '" + pred_path + "' is " + sizeText(pred) +
                             " but its ground truth '" + frame.mask_path + "' is " +
                             sizeText(truth) + " (masks are compared as they are, never resized)");
  }
  FrameScore score = scoreFrame(pred, truth, ignore);
  score.frame = frame.index;
  return score;
}

// The prediction of each ground-truth frame that has one, by frame number.
std::map<int, std::string> matched(const GtSequence& sequence,
                                   const std::map<int, std::string>& predictions,
                                   bool by_position) {
  std::map<int, std::string> result;
  for (const GtFrame& frame : sequence.frames) {
    const auto prediction =
        predictions.find(by_position ? positionOf(sequence, frame.index) : frame.index);
    if (prediction != predictions.end()) result[frame.index] = prediction->second;
  }
  return result;
}

}  // namespace

std::map<int, std::string> matchPredictions(const GtSequence& sequence,
                                            const std::string& pred_dir) {
  const std::map<int, std::string> predictions = numberedImages(pred_dir);
  return matched(sequence, predictions, numberedByPosition(sequence, predictions));
}

SequenceScore scoreSequence(const GtSequence& sequence, const std::string& pred_dir) {
  const std::map<int, std::string> predictions = numberedImages(pred_dir);
  SequenceScore score;
  score.name = sequence.name;
  score.first_frame = sequence.first_frame;
  score.matched_by_position = numberedByPosition(sequence, predictions);
  const std::map<int, std::string> matches =
      matched(sequence, predictions, score.matched_by_position);
  for (const GtFrame& frame : sequence.frames) {
    const auto prediction = matches.find(frame.index);
    if (prediction != matches.end()) {
      score.frames.push_back(scoreFiles(sequence, frame, prediction->second));
    } else if (frame.index != sequence.first_frame) {
      ++score.missing;
    }
  }
  score.skipped = countSkipped(sequence, predictions);
  return score;
}

std::vector<SequenceScore> scoreDataset(const std::vector<GtSequence>& sequences,
                                        const std::string& pred_path) {
  std::vector<SequenceScore> scores;
  for (const GtSequence& sequence : sequences) {
    scores.push_back(scoreSequence(sequence, predictionDir(sequence, pred_path)));
  }
  return scores;
}

}  // namespace movseg
